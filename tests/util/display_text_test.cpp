#include "rgbdvo/util/display_text.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

TEST_CASE("Printable escapes the bytes a terminal acts on and keeps text, other scripts too") {
  CHECK(Printable("rgb/1.png: plain") == "rgb/1.png: plain");
  CHECK(Printable("\x1b[2J\x1b]0;title\x07") == "\\x1b[2J\\x1b]0;title\\x07");
  CHECK(Printable(std::string("a\0b\n\r\tc\x7f", 8)) == "a\\x00b\\x0a\\x0d\\x09c\\x7f");
  CHECK(Printable("K\xc3\xbc"
                  "che \xe6\x97\xa5 \xf0\x9f\x98\x80") ==
        "K\xc3\xbc"
        "che \xe6\x97\xa5 \xf0\x9f\x98\x80");
  // C1 controls: CSI as one byte (not UTF-8) and as U+009B in UTF-8.
  CHECK(Printable("\x9b"
                  "31m \xc2\x9b"
                  "31m") == "\\x9b31m \\xc2\\x9b31m");
  // Not UTF-8: a lone continuation byte, a character cut short, an overlong '/', a surrogate.
  CHECK(Printable("\x80 \xe6\x97 \xc0\xaf \xed\xa0\x80") ==
        "\\x80 \\xe6\\x97 \\xc0\\xaf \\xed\\xa0\\x80");
  const std::string once = Printable("\x1b[1m\xff");
  CHECK(Printable(once) == once);
}

TEST_CASE("Excerpt quotes the start of a long line, cut where a character starts") {
  CHECK(Excerpt("1.0 rgb/1.png") == "1.0 rgb/1.png");
  const std::string line(50 << 20, 'x');
  CHECK(Excerpt(line) == std::string(80, 'x') + "...");
  // A 3-byte character across byte 80 is left out whole.
  const std::string wide = std::string(79, 'a') + "\xe6\x97\xa5" + "b";
  CHECK(Excerpt(wide) == std::string(79, 'a') + "...");
  CHECK(Excerpt(std::string(90, '\x1b'), 4) == "\\x1b\\x1b\\x1b\\x1b...");
}
