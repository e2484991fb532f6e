#include "output_files.hpp"

#include <fstream>
#include <system_error>

#include "gridloc/grids/error.hpp"

namespace gridloc::cli {

std::filesystem::path output_folder(const std::string& out) {
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (!std::filesystem::is_directory(out)) {
    throw Error("--out " + out + ": cannot create the folder" +
                (error ? " (" + error.message() + ")" : std::string()));
  }
  return {out};
}

void write_json_file(const std::filesystem::path& path, const nlohmann::json& json,
                     const std::string& what) {
  std::ofstream file(path);
  file << json.dump(2) << "\n";
  if (!file) throw Error(path.string() + ": cannot write " + what);
}

}  // namespace gridloc::cli
