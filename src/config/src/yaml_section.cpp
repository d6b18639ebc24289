#include "yaml_section.hpp"

namespace wavebench::config {

model::Sinusoid sinusoid_or(YamlSection& s, const std::string& key, Dimension dimension) {
  model::Sinusoid out;
  if (!s.has(key)) return out;
  if (!s.has_section(key)) {
    out.offset = s.quantity(key, dimension);
    return out;
  }
  YamlSection sub = s.section(key);
  out.offset = sub.quantity_or("offset", dimension, 0.0);
  out.amplitude = sub.quantity_or("amplitude", dimension, 0.0);
  out.frequency_hz = sub.non_negative_quantity_or("frequency", Dimension::kFrequency, 0.0);
  sub.require_within("frequency", out.frequency_hz, 0, kMaxSinusoidHz, "a frequency [Hz]");
  out.phase_rad = sub.quantity_or("phase", Dimension::kAngle, 0.0);
  sub.finish();
  return out;
}

YamlSection document_section(const YAML::Node& root) {
  return strict_yaml::document_section(root, "", "a YAML mapping with the sections of a twin case");
}

}  // namespace wavebench::config
