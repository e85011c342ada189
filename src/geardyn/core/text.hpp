#pragma once
// Text helpers shared by the readers and writers: reading a whole file, escaping text for HTML
// and XML, and shortening long text quoted in messages.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "geardyn/core/error.hpp"  // InputError, thrown by read_file

namespace geardyn {

/// The whole file as a string (bytes as stored), or std::nullopt when it cannot be opened or
/// read (missing, a directory, no permission).
std::optional<std::string> try_read_file(const std::filesystem::path& path);

/// The whole file as a string (bytes as stored). When it cannot be opened or read, throws
/// InputError located at the file, with `key` (e.g. "file", "ste_file"), `expected` (what the
/// file should be) and the found text "'<path>' cannot be read".
std::string read_file(const std::filesystem::path& path, const std::string& key = "file",
                      const std::string& expected = "a readable file");

/// Text for HTML element content and attribute values: & < > " ' become &amp; &lt; &gt; &quot;
/// &#39;.
std::string escape_html(std::string_view text);

/// Text for XML element content and attribute values: & < > " ' become &amp; &lt; &gt; &quot;
/// &apos;.
std::string escape_xml(std::string_view text);

/// Text for HTML element content only (quotes kept): & < > become &amp; &lt; &gt;.
std::string escape_html_content(std::string_view text);

/// Long text shortened for a message: text itself when it has at most max_chars bytes, else its
/// first max_chars - 3 bytes (never cutting a UTF-8 character) followed by "...", so that the
/// result has at most max_chars bytes. max_chars below 4 counts as 4.
std::string shorten(std::string_view text, std::size_t max_chars = 60);

}  // namespace geardyn
