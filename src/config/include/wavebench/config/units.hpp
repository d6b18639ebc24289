#pragma once
// Quantities in configs (a plain number is SI; "8 arcmin", "2680 rpm" carry a unit): the unit
// parser lives with the config reader in drivers/strict_yaml so drivers and the simulator can
// use it; these names keep the twin case's code as it was.

#include "wavebench/strict_yaml/units.hpp"

namespace wavebench::config {

using strict_yaml::accepted_units;
using strict_yaml::checked_si;
using strict_yaml::describe;
using strict_yaml::Dimension;
using strict_yaml::parse_quantity;

}  // namespace wavebench::config
