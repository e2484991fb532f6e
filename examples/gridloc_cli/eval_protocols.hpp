#pragma once
// gridloc eval's six protocols and how each runs from its parsed options: seed 001's with the
// sonar ring or a simulated laser, the drive protocol, the sector protocol, seed 002's
// disambiguation and seed 003's team protocol. `gridloc eval PROTOCOL` names one; the old
// spelling (`gridloc eval` with --laser, --drive, --protocol, polygon maps or a sector
// estimator) is mapped to one here.
#include <string>

#include "eval_disambiguation.hpp"
#include "eval_drive.hpp"
#include "eval_output.hpp"
#include "eval_team.hpp"

namespace gridloc::cli {

enum class EvalProtocol { Sonar, Laser, Drive, Sectors, Disambiguation, Team };

/// The subcommand naming `protocol`: sonar, laser, drive, sectors, disambiguation, team.
std::string protocol_name(EvalProtocol protocol);

/// The disambiguation and team protocols' own options.
struct ProtocolArgs {
  std::string name;  ///< the old spelling's --protocol: empty, disambiguation or team
  DisambiguationEvalArgs disambiguation;
  TeamEvalArgs team;
};

/// The bundled polygon maps: the sector protocol's default.
inline constexpr const char* kPolygonMaps =
    "polygons/room_rect,polygons/room_l,polygons/room_furnished,polygons/office";
/// The team protocol's default maps: the thesis's T-room and the bundled rooms.
inline constexpr const char* kTeamMaps =
    "polygons/t_room,polygons/room_rect,polygons/room_l,polygons/room_furnished";
/// The engine-in-the-loop disambiguation's default maps.
inline constexpr const char* kDisambiguationMaps = "room_symmetric,apartment_small";
/// Seed 001's default maps (sonar, laser and drive protocols).
inline constexpr const char* kRoomMaps = "room_rect,room_l,room_furnished";

/// The protocol the old spelling names: --protocol, else --drive, else the sector protocol on
/// polygon maps or with a sector estimator, else seed 001's with the laser (--laser) or the
/// sonar ring. Throws where its options contradict each other, with the messages it always
/// gave.
EvalProtocol old_spelling_protocol(const EvalArgs& args, const DriveArgs& drive,
                                   const ProtocolArgs& protocol);

/// Runs `protocol` on the options and prints its table (or JSON); throws gridloc::Error where
/// the options do not suit it (polygon maps to a grid-map protocol, and the like).
void run_protocol(EvalProtocol protocol, const EvalArgs& args, const DriveArgs& drive,
                  const ProtocolArgs& protocol_args);

}  // namespace gridloc::cli
