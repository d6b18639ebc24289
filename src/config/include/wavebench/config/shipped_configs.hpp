#pragma once
// Where the configs shipped with wavebench are (benches/, twin/, procedures/, specs/, eds/):
// $WAVEBENCH_CONFIG_DIR when set; else <executable>/../share/wavebench/configs when that
// exists (an installed wavebench, wherever it was unpacked); else the source tree's configs/
// (a build tree). One answer for every reader, so an installed daemon never reads a path of
// the machine it was built on.

#include <filesystem>

namespace wavebench::config {

std::filesystem::path shipped_config_dir();

}  // namespace wavebench::config
