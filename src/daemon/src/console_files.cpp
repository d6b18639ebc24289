#include "wavebench/daemon/console_files.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string_view>
#include <system_error>

namespace wavebench::daemon {

namespace {

struct ContentType {
  std::string_view extension, type;
};

constexpr std::array kContentTypes{
    ContentType{".html", "text/html; charset=utf-8"},
    ContentType{".js", "text/javascript; charset=utf-8"},
    ContentType{".css", "text/css; charset=utf-8"},
    ContentType{".svg", "image/svg+xml"},
    ContentType{".png", "image/png"},
    ContentType{".ico", "image/x-icon"},
    ContentType{".json", "application/json"},
    ContentType{".woff2", "font/woff2"},
};

bool safe_segment(const std::string& segment) {
  if (segment.empty() || segment.size() > 128 || segment.front() == '.') return false;
  for (const char c : segment) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

ApiResponse not_found(const std::string& path) {
  return api_error(404, "not found", "no console page at " + path);
}

}  // namespace

ConsoleFiles::ConsoleFiles(std::filesystem::path root) {
  std::error_code ec;
  auto canonical = std::filesystem::canonical(root, ec);
  if (!ec && std::filesystem::is_directory(canonical, ec)) root_ = std::move(canonical);
}

ApiResponse ConsoleFiles::answer(const HttpTarget& target) const {
  if (!enabled()) {
    return api_error(404, "not found",
                     "this daemon serves no console (no --web-root; build web/ or install the "
                     "package)");
  }
  if (target.segments.size() > 8) return not_found(target.path);
  std::filesystem::path relative;
  for (const auto& segment : target.segments) {
    if (!safe_segment(segment)) return not_found(target.path);
    relative /= segment;
  }
  if (target.segments.empty()) relative = "index.html";
  if (!relative.has_extension()) relative += ".html";
  const std::string extension = relative.extension().string();
  const ContentType* type = nullptr;
  for (const auto& t : kContentTypes) {
    if (t.extension == extension) type = &t;
  }
  if (type == nullptr) return not_found(target.path);

  std::error_code ec;
  const auto file = std::filesystem::canonical(root_ / relative, ec);
  if (ec) return not_found(target.path);
  // Inside the root after every symlink is resolved.
  const auto [root_end, file_it] =
      std::mismatch(root_.begin(), root_.end(), file.begin(), file.end());
  if (root_end != root_.end() || !std::filesystem::is_regular_file(file, ec)) {
    return not_found(target.path);
  }
  const auto size = std::filesystem::file_size(file, ec);
  if (ec || size > kMaxFileBytes) return not_found(target.path);
  std::ifstream in(file, std::ios::binary);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof())
    return api_error(500, "internal error", "cannot read " + target.path);

  ApiResponse response;
  response.raw_body = std::move(content);
  response.content_type = std::string(type->type);
  response.headers = {
      {"Cache-Control", "no-cache"},
      // The pages load only their own scripts and talk only to this daemon; no frame may hold
      // them (a cross-site page cannot overlay the stop button).
      {"Content-Security-Policy",
       "default-src 'self'; img-src 'self' data:; style-src 'self' 'unsafe-inline'; "
       "frame-ancestors 'none'; form-action 'self'; base-uri 'none'"},
      {"X-Frame-Options", "DENY"},
      {"Referrer-Policy", "no-referrer"}};
  return response;
}

std::filesystem::path default_console_root() {
  std::error_code ec;
  if (const char* dir = std::getenv("WAVEBENCH_WEB_DIR"); dir != nullptr && *dir != 0) {
    return std::filesystem::is_directory(dir, ec) ? std::filesystem::path(dir)
                                                  : std::filesystem::path();
  }
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path().parent_path() / "share" / "wavebench" / "web";
    if (std::filesystem::is_directory(installed, ec)) return installed;
  }
  // The build tree's console (src/daemon/CMakeLists.txt defines it for every build): a daemon
  // run from the build folder serves the pages it was built with.
  if (std::filesystem::is_directory(WAVEBENCH_BUILD_WEB_DIR, ec)) return WAVEBENCH_BUILD_WEB_DIR;
  return {};
}

}  // namespace wavebench::daemon
