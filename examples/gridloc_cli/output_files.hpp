#pragma once
// Where the commands that write files put them: one folder per `--out`, created if missing,
// and JSON files written the one way (issue 31: four copies of each before).
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace gridloc::cli {

/// The folder `out` names (the value of --out), created if missing; throws gridloc::Error
/// "--out OUT: cannot create the folder (why)" when it cannot be.
std::filesystem::path output_folder(const std::string& out);

/// `json` indented by 2 with a final newline at `path`; throws gridloc::Error "PATH: cannot
/// write WHAT" when it cannot be written.
void write_json_file(const std::filesystem::path& path, const nlohmann::json& json,
                     const std::string& what);

}  // namespace gridloc::cli
