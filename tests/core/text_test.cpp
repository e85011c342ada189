// core/text: reading a whole file, HTML / XML escaping and shortening text for messages.
// Exact expectations throughout: every result is a fixed string (no arithmetic, no tolerance).
#include "geardyn/core/text.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

namespace geardyn {
namespace {

namespace fs = std::filesystem;

// A fresh empty directory for one test.
fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() /
      ("geardyn_text_test_" + name + "_" +
       std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

TEST(TextReadFile, ReturnsEveryByteUnchanged) {
  const fs::path dir = scratch("bytes");
  std::string bytes = "line 1\r\nline 2\n";
  bytes += '\0';
  bytes += "\xC3\xA9 after a NUL\n";  // UTF-8 e-acute
  write(dir / "a.txt", bytes);
  EXPECT_EQ(read_file(dir / "a.txt"), bytes);
  ASSERT_TRUE(try_read_file(dir / "a.txt").has_value());
  EXPECT_EQ(*try_read_file(dir / "a.txt"), bytes);
  fs::remove_all(dir);
}

TEST(TextReadFile, AnEmptyFileIsAnEmptyString) {
  const fs::path dir = scratch("empty");
  write(dir / "empty.txt", "");
  EXPECT_EQ(read_file(dir / "empty.txt"), "");
  ASSERT_TRUE(try_read_file(dir / "empty.txt").has_value());
  EXPECT_TRUE(try_read_file(dir / "empty.txt")->empty());
  fs::remove_all(dir);
}

TEST(TextReadFile, AMissingFileIsAnInputErrorNamingIt) {
  const fs::path dir = scratch("missing");
  const fs::path missing = dir / "no_such_file.csv";
  EXPECT_FALSE(try_read_file(missing).has_value());
  try {
    (void)read_file(missing, "ste_file", "a readable CSV file");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, missing.string());
    EXPECT_EQ(e.key_path(), "ste_file");
    EXPECT_EQ(e.expected(), "a readable CSV file");
    EXPECT_EQ(e.found(), "'" + missing.string() + "' cannot be read");
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos);
  }
  fs::remove_all(dir);
}

TEST(TextReadFile, ADirectoryCannotBeRead) {
  const fs::path dir = scratch("directory");
  EXPECT_FALSE(try_read_file(dir).has_value());
  try {
    (void)read_file(dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "file");
    EXPECT_EQ(e.expected(), "a readable file");
    EXPECT_EQ(e.found(), "'" + dir.string() + "' cannot be read");
  }
  fs::remove_all(dir);
}

TEST(TextEscape, HtmlReplacesTheFiveSpecialCharacters) {
  EXPECT_EQ(escape_html("<a href='x'>\"&\"</a>"),
            "&lt;a href=&#39;x&#39;&gt;&quot;&amp;&quot;&lt;/a&gt;");
  EXPECT_EQ(escape_html("plain text 1.5 m/s"), "plain text 1.5 m/s");
  EXPECT_EQ(escape_html(""), "");
  // An existing reference is escaped again: the text is shown literally.
  EXPECT_EQ(escape_html("&amp;"), "&amp;amp;");
  // Non-ASCII bytes pass through unchanged.
  EXPECT_EQ(escape_html("\xCE\xBC m < 1"), "\xCE\xBC m &lt; 1");
}

TEST(TextEscape, XmlUsesApos) {
  EXPECT_EQ(escape_xml("<a b='c' d=\"e\">&</a>"),
            "&lt;a b=&apos;c&apos; d=&quot;e&quot;&gt;&amp;&lt;/a&gt;");
  EXPECT_EQ(escape_xml("displacement_x"), "displacement_x");
}

TEST(TextEscape, HtmlContentKeepsQuotes) {
  EXPECT_EQ(escape_html_content("F < 2 & x > 1 \"q\" 'a'"), "F &lt; 2 &amp; x &gt; 1 \"q\" 'a'");
}

TEST(TextShorten, ShortTextIsUnchanged) {
  EXPECT_EQ(shorten(""), "");
  EXPECT_EQ(shorten(std::string(60, 'a')), std::string(60, 'a'));
  EXPECT_EQ(shorten("abcdef", 6), "abcdef");
}

TEST(TextShorten, LongTextKeepsItsStartAndEndsWithAnEllipsis) {
  const std::string long_text(61, 'b');
  EXPECT_EQ(shorten(long_text), std::string(57, 'b') + "...");
  EXPECT_EQ(shorten(long_text).size(), 60u);
  EXPECT_EQ(shorten("abcdefgh", 6), "abc...");
  EXPECT_EQ(shorten(std::string(44, 'c'), 43), std::string(40, 'c') + "...");
}

TEST(TextShorten, NeverCutsAUtf8Character) {
  // "ab" then e-acute (2 bytes, at bytes 2-3) then more: a cut after 3 bytes would split it.
  const std::string text =
      "ab\xC3\xA9"
      "cdefgh";
  EXPECT_EQ(shorten(text, 6), "ab...");
  EXPECT_EQ(shorten(text, 7), "ab\xC3\xA9...");
}

TEST(TextShorten, TinyLimitsCountAsFour) {
  EXPECT_EQ(shorten("abcdef", 0), "a...");
  EXPECT_EQ(shorten("abcd", 1), "abcd");
}

}  // namespace
}  // namespace geardyn
