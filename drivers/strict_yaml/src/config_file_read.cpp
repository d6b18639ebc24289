// Reading a config file: only a regular file, only up to the size bound, so a folder, a FIFO
// or /dev/zero given as a config is refused instead of read as empty text or forever.
#include <fstream>
#include <iterator>
#include <system_error>

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::strict_yaml {

std::string read_config_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string source = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    throw RefusedConfig("(file)", source, "an existing config file", source);
  }
  if (fs::is_directory(status)) {
    throw RefusedConfig("(file)", source, "a config file, not a folder", source);
  }
  if (!fs::is_regular_file(status)) {
    throw RefusedConfig("(file)", source, "a regular config file (not a device, FIFO or socket)",
                        source);
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size > kMaxConfigBytes) {
    throw RefusedConfig("(file)", std::to_string(size) + " bytes",
                        "a config of at most " + std::to_string(kMaxConfigBytes) + " bytes",
                        source);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RefusedConfig("(file)", source, "a readable config file", source);
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  // Bounded even if the file grows while it is read.
  char buffer[8192];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxConfigBytes) {
      throw RefusedConfig("(file)", "more than " + std::to_string(kMaxConfigBytes) + " bytes",
                          "a config of at most " + std::to_string(kMaxConfigBytes) + " bytes",
                          source);
    }
  }
  if (in.bad()) throw RefusedConfig("(file)", source, "a readable config file", source);
  return text;
}

}  // namespace wavebench::strict_yaml
