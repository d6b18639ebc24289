#include "wavebench/simdevices/simulated_bench_config.hpp"

#include <cctype>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::simdevices {
namespace {

using strict_yaml::set_if;
using strict_yaml::YamlSection;

// [numerator, denominator] of a factor group object. 0 and values >= 2^31 are taken: they
// model a drive whose factor group a master must refuse.
void read_fraction(YamlSection& s, const char* key, std::uint32_t& numerator,
                   std::uint32_t& denominator) {
  const auto v = s.optional_integer_list(key, 0, 0xFFFFFFFFLL);
  if (!v) return;
  if (v->size() != 2) {
    s.fail(key, s.value_text(key), "[numerator, denominator], two integers in 0..4294967295");
  }
  numerator = static_cast<std::uint32_t>((*v)[0]);
  denominator = static_cast<std::uint32_t>((*v)[1]);
}

// "0x6064:0/32": index, sub-index, length in bits; whole bytes, as the simulated node sends them.
std::optional<PdoMappingEntry> parse_mapping_entry(const std::string& text) {
  try {
    std::size_t used = 0;
    const unsigned long index = std::stoul(text, &used, 0);
    if (used >= text.size() || text[used] != ':') return std::nullopt;
    std::size_t rest = used + 1;
    const unsigned long sub = std::stoul(text.substr(rest), &used, 0);
    rest += used;
    if (rest >= text.size() || text[rest] != '/') return std::nullopt;
    const unsigned long bits = std::stoul(text.substr(rest + 1), &used, 10);
    if (rest + 1 + used != text.size()) return std::nullopt;
    if (index == 0 || index > 0xFFFF || sub > 0xFF || bits == 0 || bits > 64 || bits % 8 != 0)
      return std::nullopt;
    return PdoMappingEntry{static_cast<std::uint16_t>(index), static_cast<std::uint8_t>(sub),
                           static_cast<std::uint8_t>(bits)};
  } catch (const std::logic_error&) {
    return std::nullopt;
  }
}

// fixed_tpdo_mapping: {tpdo1: ["0x6064:0/32", "0x6041:0/16"], tpdo2: ["0x606C:0/32"]}
void read_fixed_tpdos(YamlSection& s, std::vector<FixedTpdo>& out) {
  auto f = s.optional_section("fixed_tpdo_mapping");
  if (!f) return;
  out.clear();
  for (int n = 1; n <= 4; ++n) {
    const std::string key = "tpdo" + std::to_string(n);
    const auto list = f->optional_text_list(key);
    if (!list) continue;
    FixedTpdo fixed{n, {}};
    unsigned bits = 0;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const auto entry = parse_mapping_entry((*list)[i]);
      if (!entry) {
        f->fail(key + "[" + std::to_string(i) + "]", (*list)[i],
                "INDEX:SUB/BITS like \"0x6064:0/32\", BITS a multiple of 8 up to 64");
      }
      bits += entry->bits;
      fixed.mapping.push_back(*entry);
    }
    if (list->size() > 8 || bits > 64)
      f->fail(key, f->value_text(key), "at most 8 objects of together at most 64 bits");
    out.push_back(std::move(fixed));
  }
  f->finish();
}

void read_factor_group(YamlSection& s, DriveFactorGroupConfig& f) {
  read_fraction(s, "position_encoder_resolution", f.position_encoder_increments,
                f.position_encoder_revolutions);
  read_fraction(s, "velocity_encoder_resolution", f.velocity_encoder_increments,
                f.velocity_encoder_revolutions);
  read_fraction(s, "gear_ratio", f.gear_motor_revolutions, f.gear_shaft_revolutions);
  read_fraction(s, "feed_constant", f.feed, f.feed_shaft_revolutions);
  s.finish();
}

void read_drive_units(YamlSection& s, ServoDriveConfig& d) {
  if (const auto v =
          s.optional_choice("velocity_unit", {"counts/s", "rpm", "0.1 rpm", "factor_group"})) {
    d.velocity_unit = *v == "counts/s"  ? DriveVelocityUnit::kCounts
                      : *v == "rpm"     ? DriveVelocityUnit::kRpm
                      : *v == "0.1 rpm" ? DriveVelocityUnit::kDeciRpm
                                        : DriveVelocityUnit::kFactorGroup;
  }
  if (auto f = s.optional_section("factor_group")) read_factor_group(*f, d.factor_group);
  if (const auto si = s.optional_boolean("si_unit_objects")) d.si_unit_objects = *si;
  if (const auto objects = s.optional_text_list("absent_objects")) {
    d.absent_objects.clear();
    for (std::size_t i = 0; i < objects->size(); ++i) {
      const std::string& text = (*objects)[i];
      std::string upper = text;
      for (auto& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      if (upper == "0X60F4") {
        d.absent_objects.push_back(0x60F4);
      } else if (upper == "0X6077") {
        d.absent_objects.push_back(0x6077);
      } else if (upper == "0X603F") {
        d.absent_objects.push_back(0x603F);
      } else if (upper == "0X1018:4") {
        d.identity.has_serial_number = false;
      } else {
        s.fail("absent_objects[" + std::to_string(i) + "]", text,
               "one of the optional objects \"0x60F4\", \"0x6077\", \"0x603F\", "
               "\"0x1018:4\"");
      }
    }
  }
}

void read_drive(YamlSection& s, ServoDriveConfig& d) {
  read_drive_units(s, d);
  read_fixed_tpdos(s, d.fixed_tpdos);
  set_if(s.optional_integer("node_id", 1, 127), d.node_id);
  set_if(s.optional_integer("counts_per_revolution", 4, 1LL << 30), d.counts_per_revolution);
  set_if(s.optional_number("rated_torque_nm", 1e-3, 1e4), d.rated_torque_nm);
  set_if(s.optional_integer("max_torque_permille", 1, 65535), d.max_torque_permille);
  set_if(s.optional_integer("max_motor_speed_rpm", 1, 100000), d.max_motor_speed_rpm);
  set_if(s.optional_number("position_gain", 0, 1e6), d.position_gain);
  set_if(s.optional_number("velocity_gain", 0, 1e6), d.velocity_gain);
  set_if(s.optional_number("velocity_integral_time_s", 0, 1e3), d.velocity_integral_time);
  if (const auto us = s.optional_number("control_period_us", 10, 10000)) {
    d.control_period = *us * 1e-6;
  }
  set_if(s.optional_integer("quick_stop_option", 0, 8), d.quick_stop_option);
  set_if(s.optional_integer("following_error_window", 0, 0xFFFFFFFFLL), d.following_error_window);
  set_if(s.optional_integer("following_error_timeout_ms", 0, 65535), d.following_error_timeout_ms);
  set_if(s.optional_integer("serial_number", 0, 0xFFFFFFFFLL), d.identity.serial_number);
  if (const auto v = s.optional_boolean("heartbeat_producer")) d.identity.heartbeat_producer = *v;
  s.finish();
}

void read_encoder(YamlSection& s, EncoderConfig& e) {
  set_if(s.optional_integer("node_id", 1, 127), e.node_id);
  set_if(s.optional_integer("resolution", 2, 1LL << 31), e.single_turn_resolution);
  set_if(s.optional_integer("revolutions", 1, 65535), e.revolutions);
  if (const auto arcsec = s.optional_number("noise_arcsec", 0, 3600)) {
    e.noise_rad = *arcsec * std::numbers::pi / (180 * 3600);
  }
  set_if(s.optional_integer("seed", 0, std::numeric_limits<long long>::max()), e.seed);
  set_if(s.optional_integer("serial_number", 0, 0xFFFFFFFFLL), e.identity.serial_number);
  read_fixed_tpdos(s, e.fixed_tpdos);
  if (const auto v = s.optional_boolean("heartbeat_producer")) e.identity.heartbeat_producer = *v;
  s.finish();
}

// "0x6130:1" or "0x6130" (sub-index 0). Hand-written: the CiA 306 notation has no parser here.
void read_object(YamlSection& s, TorqueSensorConfig& t) {
  const auto text = s.optional_text("object");
  if (!text) return;
  try {
    std::size_t used = 0;
    const unsigned long index = std::stoul(*text, &used, 0);
    unsigned long sub = 0;
    if (used < text->size()) {
      if ((*text)[used] != ':') throw std::invalid_argument("separator");
      std::size_t used_sub = 0;
      sub = std::stoul(text->substr(used + 1), &used_sub, 0);
      if (used + 1 + used_sub != text->size()) throw std::invalid_argument("trailing");
    }
    if (index < 0x2000 || index > 0xFFFF || sub > 0xFF) throw std::out_of_range("range");
    t.index = static_cast<std::uint16_t>(index);
    t.sub = static_cast<std::uint8_t>(sub);
  } catch (const std::logic_error&) {
    s.fail("object", *text, "INDEX[:SUB] like \"0x6130:1\" with 0x2000 <= INDEX <= 0xFFFF");
  }
}

void read_torque_sensor(YamlSection& s, TorqueSensorConfig& t) {
  set_if(s.optional_integer("node_id", 1, 127), t.node_id);
  read_object(s, t);
  if (const auto type = s.optional_text("type")) {
    try {
      t.type = parse_process_value_type(*type);
    } catch (const std::invalid_argument&) {
      s.fail("type", *type, "i16, i32 or f32");
    }
  }
  set_if(s.optional_number("scale", 1e-12, 1e6), t.scale_nm_per_unit);
  set_if(s.optional_number("noise_nm", 0, 1e4), t.noise_nm);
  set_if(s.optional_number("offset_nm", -1e6, 1e6), t.offset_nm);
  set_if(s.optional_integer("seed", 0, std::numeric_limits<long long>::max()), t.seed);
  read_fixed_tpdos(s, t.fixed_tpdos);
  if (const auto v = s.optional_boolean("heartbeat_producer")) t.identity.heartbeat_producer = *v;
  s.finish();
}

}  // namespace

SimulatedBenchConfig read_simulated_bench_section(YamlSection& sb, SimulatedBenchConfig base) {
  if (const auto c = sb.optional_choice("clock", {"realtime", "sync", "manual"})) {
    base.clock = *c == "realtime" ? BenchClock::kRealTime
                 : *c == "sync"   ? BenchClock::kSyncDriven
                                  : BenchClock::kManual;
  }
  if (const auto us = sb.optional_number("sync_period_us", 10, 1e6)) base.sync_period = *us * 1e-6;
  set_if(sb.optional_number("brake_torque_nm", 0, 1e6), base.brake_torque);
  if (auto d = sb.optional_section("drive")) read_drive(*d, base.drive);
  if (auto e = sb.optional_section("encoder")) read_encoder(*e, base.encoder);
  if (auto t = sb.optional_section("torque_sensor")) read_torque_sensor(*t, base.torque_sensor);
  if (auto e = sb.optional_section("input_encoder")) {
    if (!base.input_encoder) {
      EncoderConfig input;
      input.node_id = 5;
      input.identity.device_name = "WB-SIM input encoder";
      input.identity.product_code = 0x00000A58;
      input.revolutions = 1;  // single-turn on the fast shaft: it wraps every input turn
      input.seed = 5;
      base.input_encoder = input;
    }
    read_encoder(*e, *base.input_encoder);
  }
  sb.finish();
  const std::uint8_t ids[] = {base.drive.node_id, base.encoder.node_id, base.torque_sensor.node_id};
  if (ids[0] == ids[1] || ids[0] == ids[2] || ids[1] == ids[2]) {
    sb.fail("*.node_id",
            std::to_string(ids[0]) + ", " + std::to_string(ids[1]) + ", " + std::to_string(ids[2]),
            "three different node ids");
  }
  if (base.input_encoder &&
      (base.input_encoder->node_id == ids[0] || base.input_encoder->node_id == ids[1] ||
       base.input_encoder->node_id == ids[2])) {
    sb.fail("input_encoder.node_id", std::to_string(base.input_encoder->node_id),
            "a node id no other simulated device uses");
  }
  return base;
}

DataType parse_process_value_type(const std::string& text) {
  if (text == "i16" || text == "int16") return DataType::kInteger16;
  if (text == "i32" || text == "int32") return DataType::kInteger32;
  if (text == "f32" || text == "real32") return DataType::kReal32;
  throw std::invalid_argument("process value type '" + text + "' (expected i16, i32 or f32)");
}

SimulatedBenchConfig parse_simulated_bench_config(const std::string& yaml_text,
                                                  SimulatedBenchConfig base) {
  return parse_simulated_bench_config(yaml_text, "simbench config", std::move(base));
}

SimulatedBenchConfig parse_simulated_bench_config(const std::string& yaml_text,
                                                  const std::string& source,
                                                  SimulatedBenchConfig base) {
  try {
    YamlSection root = strict_yaml::document_section(
        strict_yaml::parse_strict_yaml(yaml_text, source), source, "a map with a simbench section");
    // Other top-level keys are the business of whoever else reads the file.
    auto sb = root.optional_section("simbench");
    return sb ? read_simulated_bench_section(*sb, std::move(base)) : base;
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
}

SimulatedBenchConfig load_simulated_bench_config(const std::filesystem::path& path,
                                                 SimulatedBenchConfig base) {
  std::string text;
  try {
    text = strict_yaml::read_config_file(path);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
  return parse_simulated_bench_config(text, path.string(), std::move(base));
}

}  // namespace wavebench::simdevices
