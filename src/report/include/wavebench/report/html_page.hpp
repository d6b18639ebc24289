#pragma once
// A self-contained HTML page built from escaped text: headings, paragraphs, tables and images
// linked by relative path, one inline style sheet.

#include <string>
#include <string_view>
#include <vector>

namespace wavebench::report {

// &, <, >, " and ' as entities; everything that reaches the page from a run goes through it.
std::string html_escape(std::string_view text);

struct HtmlCell {
  std::string text;
  std::string href;    // makes the cell a link when not empty
  bool alert = false;  // shown in red (an aborted status, a failed limit)
};

struct HtmlTable {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<HtmlCell>> rows;
};

class HtmlPage {
 public:
  explicit HtmlPage(std::string title);

  HtmlPage& heading(const std::string& text, int level = 2);
  HtmlPage& paragraph(const std::string& text, bool alert = false);
  // "label: value" lines of a header block.
  HtmlPage& facts(const std::vector<std::pair<std::string, HtmlCell>>& facts);
  HtmlPage& table(const HtmlTable& table);
  HtmlPage& image(const std::string& relative_path, const std::string& alt);
  HtmlPage& list(const std::vector<std::string>& items);

  std::string str() const;

 private:
  std::string title_;
  std::string body_;
};

// "-1.62" with `decimals` decimals; "–" for a missing value.
std::string fixed(double value, int decimals);
// Three significant digits and an exponent when large ("1.23e+05").
std::string general(double value, int digits = 4);

}  // namespace wavebench::report
