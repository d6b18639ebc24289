#include "wavebench/figures/figure_path.hpp"

#include <sstream>

namespace wavebench::figures {

namespace {

std::vector<std::string> split(const std::string& path) {
  std::vector<std::string> out;
  std::string part;
  std::istringstream in(path);
  while (std::getline(in, part, '.')) out.push_back(part);
  return out;
}

// "reverse 60 N·m", "mesh": what an array element is, from the keys that name one.
std::string element_label(const nlohmann::json& e) {
  std::ostringstream s;
  if (!e.is_object()) return {};
  if (const auto d = e.find("direction"); d != e.end() && d->is_string())
    s << " " << d->get<std::string>();
  if (const auto n = e.find("name"); n != e.end() && n->is_string())
    s << " " << n->get<std::string>();
  if (const auto l = e.find("load_nm"); l != e.end() && l->is_number()) {
    s << " " << l->get<double>() << " N·m";
  }
  return s.str();
}

void walk(const nlohmann::json& node, const std::vector<std::string>& parts, std::size_t i,
          const std::string& path, const std::string& where, std::vector<FigureAt>& out) {
  if (!node.is_object()) return;
  std::string key = parts[i];
  const bool every = key.size() > 3 && key.ends_with("[*]");
  if (every) key.resize(key.size() - 3);
  const auto it = node.find(key);
  if (it == node.end()) return;
  const std::string here = path.empty() ? key : path + "." + key;
  if (every) {
    if (!it->is_array()) return;
    for (std::size_t k = 0; k < it->size(); ++k) {
      const std::string p = here + "[" + std::to_string(k) + "]";
      if (i + 1 < parts.size()) walk((*it)[k], parts, i + 1, p, p + element_label((*it)[k]), out);
    }
    return;
  }
  if (i + 1 < parts.size()) {
    walk(*it, parts, i + 1, here, where, out);
    return;
  }
  if (it->is_null()) return;
  FigureAt f;
  f.path = here;
  f.where = where.empty() ? here : where;
  f.value = &*it;
  const auto u = node.find("uncertainty");
  if (u != node.end() && u->is_object()) {
    if (const auto beside = u->find(key); beside != u->end()) f.uncertainty = &*beside;
  }
  out.push_back(std::move(f));
}

}  // namespace

std::vector<FigureAt> find_figure_values(const nlohmann::json& results, const std::string& path) {
  std::vector<FigureAt> out;
  const auto parts = split(path);
  if (!parts.empty()) walk(results, parts, 0, "", "", out);
  return out;
}

std::optional<double> number_of(const nlohmann::json& value) {
  if (value.is_number()) return value.get<double>();
  if (value.is_object()) {
    if (const auto v = value.find("value"); v != value.end() && v->is_number()) {
      return v->get<double>();
    }
  }
  return std::nullopt;
}

}  // namespace wavebench::figures
