#include "geardyn/core/text.hpp"

#include <fstream>
#include <sstream>

namespace geardyn {

std::optional<std::string> try_read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return content.str();
}

std::string read_file(const std::filesystem::path& path, const std::string& key,
                      const std::string& expected) {
  std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(SourceLocation{path.string(), 0, 0}, key, expected,
                     "'" + path.string() + "' cannot be read");
  return std::move(*text);
}

namespace {

// Replaces & < > always, and " ' by the given references when they are not null.
std::string escape(std::string_view text, const char* quote, const char* apostrophe) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (char c : text) {
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
        if (quote)
          out += quote;
        else
          out += c;
        break;
      case '\'':
        if (apostrophe)
          out += apostrophe;
        else
          out += c;
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string escape_html(std::string_view text) { return escape(text, "&quot;", "&#39;"); }

std::string escape_xml(std::string_view text) { return escape(text, "&quot;", "&apos;"); }

std::string escape_html_content(std::string_view text) { return escape(text, nullptr, nullptr); }

std::string shorten(std::string_view text, std::size_t max_chars) {
  if (max_chars < 4) max_chars = 4;
  if (text.size() <= max_chars) return std::string(text);
  std::size_t keep = max_chars - 3;
  // Back off to the start of a UTF-8 character (continuation bytes are 10xxxxxx).
  while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80) --keep;
  return std::string(text.substr(0, keep)) + "...";
}

}  // namespace geardyn
