// Parsing with the checks yaml-cpp does not make. Hand-written because yaml-cpp has no option
// to refuse duplicate keys (its maps keep both pairs and lookups return the first).
#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::strict_yaml {
namespace {

constexpr const char* kDocument = "(document)";

std::string escaped(const std::string& s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c >= 0x7F) {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xF];
    } else {
      out += ch;
    }
  }
  return out;
}

struct Line {
  std::size_t begin = 0, end = 0;
};

std::vector<Line> split_lines(const std::string& text, std::size_t up_to) {
  std::vector<Line> lines;
  std::size_t begin = 0;
  while (begin <= up_to && begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    lines.push_back({begin, end});
    begin = end + 1;
  }
  return lines;
}

// "  - name: x" -> indent 4 (the list marker counts as indentation), key "name".
bool block_key(const std::string& text, const Line& line, std::size_t& indent, std::string& key) {
  std::size_t i = line.begin;
  while (i < line.end && (text[i] == ' ' || text[i] == '-')) ++i;
  if (i == line.end || text[i] == '#') return false;
  indent = i - line.begin;
  const std::size_t colon = text.find(':', i);
  if (colon == std::string::npos || colon >= line.end) return false;
  key = text.substr(i, colon - i);
  while (!key.empty() && key.back() == ' ') key.pop_back();
  if (key.size() >= 2 && (key.front() == '"' || key.front() == '\'')) {
    key = key.substr(1, key.size() - 2);
  }
  return !key.empty() && first_non_utf8_byte(key) == key.size();
}

// The key path of the block-style line holding byte `at`, found by indentation: enough to point
// a user at the line with a bad byte, which yaml-cpp never sees as an error.
std::string key_path_at(const std::string& text, std::size_t at) {
  const std::vector<Line> lines = split_lines(text, at);
  if (lines.empty()) return kDocument;
  std::vector<std::string> path;
  std::size_t indent = 0;
  std::string key;
  std::size_t limit = std::string::npos;
  // A key with the bad byte in it is no key: the path then ends at its parent.
  if (block_key(text, lines.back(), indent, key)) {
    path.push_back(key);
    limit = indent;
  } else {
    std::size_t i = lines.back().begin;
    while (i < lines.back().end && (text[i] == ' ' || text[i] == '-')) ++i;
    limit = i - lines.back().begin;
  }
  for (std::size_t n = lines.size() - 1; n-- > 0 && limit > 0;) {
    if (block_key(text, lines[n], indent, key) && indent < limit) {
      path.push_back(key);
      limit = indent;
    }
  }
  if (path.empty()) return kDocument;
  std::string joined;
  for (auto it = path.rbegin(); it != path.rend(); ++it)
    joined += (joined.empty() ? "" : ".") + *it;
  return joined;
}

void refuse_non_utf8(const std::string& text, std::size_t at, const std::string& source) {
  const std::vector<Line> lines = split_lines(text, at);
  const Line line = lines.empty() ? Line{0, 0} : lines.back();
  std::size_t line_end = line.end;
  if (line_end > line.begin + 120) line_end = std::max(at + 1, line.begin + 120);
  const std::string shown = escaped(text.substr(line.begin, line_end - line.begin));
  char byte[8];
  std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[at]));
  throw RefusedConfig(key_path_at(text, at), shown,
                      std::string("UTF-8 text without control characters (byte ") + byte +
                          " at line " + std::to_string(lines.size()) + ", column " +
                          std::to_string(at - line.begin + 1) + " is not)",
                      source);
}

// YAML::LoadAll of yaml-cpp 0.7 loops forever, allocating, on a stray ',' (fuzz finding: the
// two bytes ",'"), so the text is parsed with YAML::Load and a second document is found here:
// a "---" line after content.
std::size_t second_document_line(const std::string& text) {
  bool content = false;
  std::size_t line = 1;
  for (std::size_t begin = 0; begin < text.size(); ++line) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string l = text.substr(begin, end - begin);
    const bool marker =
        l.rfind("---", 0) == 0 && (l.size() == 3 || l[3] == ' ' || l[3] == '\t' || l[3] == '\r');
    if (marker && content) return line;
    const std::size_t first = l.find_first_not_of(" \t\r");
    if (!marker && first != std::string::npos && l[first] != '#' && l[first] != '%') {
      content = true;
    }
    if (marker && l.find_first_not_of(" \t\r", 3) != std::string::npos &&
        l[l.find_first_not_of(" \t\r", 3)] != '#') {
      content = true;  // "--- value"
    }
    begin = end + 1;
  }
  return 0;
}

std::string shape(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  if (n.IsMap()) return "a mapping";
  if (n.IsSequence()) return "a list";
  return "";
}

std::string line_of(const YAML::Node& n) {
  return "line " + std::to_string(n.Mark().line + 1);
}

class TreeWalk {
 public:
  explicit TreeWalk(const std::string& source) : source_(source) {}

  void visit(const YAML::Node& node, const std::string& path, int depth) {
    const std::string where = path.empty() ? kDocument : path;
    if (++visits_ > kMaxNodeVisits) {
      throw RefusedConfig(where, "more than " + std::to_string(kMaxNodeVisits) + " nodes",
                          "a config of at most " + std::to_string(kMaxNodeVisits) +
                              " nodes (an alias counts each time it is used)",
                          source_);
    }
    if (depth > kMaxDepth) {
      throw RefusedConfig(
          where, "nesting " + std::to_string(depth) + " deep at " + line_of(node),
          "mappings and lists nested at most " + std::to_string(kMaxDepth) + " deep", source_);
    }
    if (node.IsSequence()) {
      std::size_t i = 0;
      for (const auto& item : node) {
        visit(item, where + "[" + std::to_string(i++) + "]", depth + 1);
      }
    } else if (node.IsMap()) {
      std::map<std::string, YAML::Mark> seen;
      for (const auto& kv : node) {
        if (!kv.first.IsScalar()) {
          throw RefusedConfig(where, shape(kv.first) + " as a key at " + line_of(kv.first),
                              "plain text keys", source_);
        }
        const std::string& key = kv.first.Scalar();
        const std::string key_path = path.empty() ? key : path + "." + key;
        const auto [it, fresh] = seen.emplace(key, kv.first.Mark());
        if (!fresh) {
          throw RefusedConfig(key_path, shape(kv.second),
                              "each key once in its mapping ('" + key + "' is on line " +
                                  std::to_string(it->second.line + 1) + " and line " +
                                  std::to_string(kv.first.Mark().line + 1) + ")",
                              source_);
        }
        visit(kv.second, key_path, depth + 1);
      }
    }
  }

 private:
  const std::string& source_;
  std::size_t visits_ = 0;
};

}  // namespace

YAML::Node parse_strict_yaml(const std::string& text, const std::string& source) {
  if (text.size() > kMaxConfigBytes) {
    throw RefusedConfig(kDocument, std::to_string(text.size()) + " bytes",
                        "a config of at most " + std::to_string(kMaxConfigBytes) + " bytes",
                        source);
  }
  if (const std::size_t bad = first_non_utf8_byte(text); bad != text.size()) {
    refuse_non_utf8(text, bad, source);
  }
  if (const std::size_t line = second_document_line(text); line != 0) {
    throw RefusedConfig(kDocument, "a second document at line " + std::to_string(line),
                        "one YAML document (a second '---' starts another)", source);
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw RefusedConfig(kDocument,
                        "nesting deeper than " + std::to_string(e.depth()) + " at line " +
                            std::to_string(e.mark.line + 1),
                        "mappings and lists nested at most " + std::to_string(kMaxDepth) + " deep",
                        source);
  } catch (const YAML::Exception& e) {
    throw RefusedConfig(kDocument,
                        "line " + std::to_string(e.mark.line + 1) + ", column " +
                            std::to_string(e.mark.column + 1) + ": " + e.msg,
                        "well-formed YAML", source);
  }
  if (!root.IsDefined() || root.IsNull()) {
    const std::string start = text.substr(0, 60);
    throw RefusedConfig(kDocument, escaped(start),
                        "a config with at least one key (the file is empty, blank or only "
                        "comments)",
                        source);
  }
  TreeWalk(source).visit(root, "", 0);
  return root;
}

}  // namespace wavebench::strict_yaml
