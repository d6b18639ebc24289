#include "wavebench/report/html_page.hpp"

#include <cmath>
#include <cstdio>

namespace wavebench::report {
namespace {

std::string cell_html(const HtmlCell& cell) {
  std::string inner = html_escape(cell.text);
  if (!cell.href.empty()) inner = "<a href=\"" + html_escape(cell.href) + "\">" + inner + "</a>";
  if (cell.alert) inner = "<span class=\"alert\">" + inner + "</span>";
  return inner;
}

constexpr const char* kStyle =
    "body{font-family:sans-serif;margin:2em;color:#222;max-width:1500px}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}"
    "th,td{border:1px solid #bbb;padding:3px 8px;text-align:right}"
    "th{background:#eee}td:first-child,th:first-child{text-align:left}"
    "caption{text-align:left;font-weight:bold;padding:4px 0}"
    ".alert{color:#c00;font-weight:bold}.facts td{border:none;text-align:left}"
    "img{max-width:100%;border:1px solid #ddd;margin:0.5em 0 1.5em}";

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) {}

HtmlPage& HtmlPage::heading(const std::string& text, int level) {
  const std::string tag = "h" + std::to_string(level < 1 ? 1 : level > 4 ? 4 : level);
  body_ += "<" + tag + ">" + html_escape(text) + "</" + tag + ">\n";
  return *this;
}

HtmlPage& HtmlPage::paragraph(const std::string& text, bool alert) {
  body_ += alert ? "<p class=\"alert\">" : "<p>";
  body_ += html_escape(text) + "</p>\n";
  return *this;
}

HtmlPage& HtmlPage::facts(const std::vector<std::pair<std::string, HtmlCell>>& facts) {
  body_ += "<table class=\"facts\">\n";
  for (const auto& [label, value] : facts) {
    body_ += "<tr><td>" + html_escape(label) + "</td><td>" + cell_html(value) + "</td></tr>\n";
  }
  body_ += "</table>\n";
  return *this;
}

HtmlPage& HtmlPage::table(const HtmlTable& table) {
  body_ += "<table>\n";
  if (!table.caption.empty()) body_ += "<caption>" + html_escape(table.caption) + "</caption>\n";
  body_ += "<tr>";
  for (const auto& h : table.header) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : table.rows) {
    body_ += "<tr>";
    for (const auto& cell : row) body_ += "<td>" + cell_html(cell) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
  return *this;
}

HtmlPage& HtmlPage::image(const std::string& relative_path, const std::string& alt) {
  body_ += "<img src=\"" + html_escape(relative_path) + "\" alt=\"" + html_escape(alt) + "\">\n";
  return *this;
}

HtmlPage& HtmlPage::list(const std::vector<std::string>& items) {
  body_ += "<ul>\n";
  for (const auto& item : items) body_ += "<li>" + html_escape(item) + "</li>\n";
  body_ += "</ul>\n";
  return *this;
}

std::string HtmlPage::str() const {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
         html_escape(title_) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" +
         html_escape(title_) + "</h1>\n" + body_ + "</body>\n</html>\n";
}

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "\u2013";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  if (std::string(buf).find_first_not_of("-0.") == std::string::npos) {
    std::snprintf(buf, sizeof buf, "%.*f", decimals, 0.0);  // no "-0.00"
  }
  return buf;
}

std::string general(double value, int digits) {
  if (!std::isfinite(value)) return "\u2013";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

}  // namespace wavebench::report
