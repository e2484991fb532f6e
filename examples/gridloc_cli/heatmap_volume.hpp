#pragma once
// The score volume of `gridloc heatmap` on disk (issue 4): the scores as a NumPy .npy file and
// volume.json, which says how they are laid out.
#include <nlohmann/json.hpp>
#include <string>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc::cli {

/// NumPy .npy v1.0: magic, version, header length, a Python dict padded with spaces to a
/// multiple of 64 bytes ending in '\n', then little-endian float32 in C order.
void write_npy(const std::string& path, const ScoreVolume& volume);

/// volume.json: how scores.npy is laid out (shape, axes, the map grid), the best pose, the
/// mass of each heading, the window and the files.
nlohmann::json volume_json(const ScoreVolume& volume, const SearchWindow& window,
                           const nlohmann::json& files);

}  // namespace gridloc::cli
