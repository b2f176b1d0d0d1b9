// ClippedText (core/clipped_text.h): whole when short; cut never inside a
// UTF-8 character or an option mark, with "..." where cut.
#include "core/clipped_text.h"

#include <string>

#include <catch2/catch.hpp>

using namespace driveid;

TEST_CASE("clipped text: short whole, cut at a character and outside the marks") {
  CHECK(ClippedText("short", 10) == "short");
  CHECK(ClippedText("0123456789abc", 10) == "0123456...");
  // The cut would fall inside "‹params›": the mark is left out whole.
  const std::string mark = "fix it in \u2039params\u203A or log more";
  for (std::size_t bytes = 12; bytes < mark.size(); ++bytes) {
    const std::string cut = ClippedText(mark, bytes);
    CHECK(cut.size() <= bytes);
    const bool opened = cut.find("\u2039") != std::string::npos, closed = cut.find("\u203A") != std::string::npos;
    CHECK(opened == closed);
    // Valid UTF-8: no sequence is cut (a lead byte 0xE2 has its two continuations).
    for (std::size_t k = 0; k < cut.size(); ++k) {
      if (static_cast<unsigned char>(cut[k]) == 0xE2) {
        REQUIRE(k + 2 < cut.size());
        CHECK((static_cast<unsigned char>(cut[k + 1]) & 0xC0) == 0x80);
      }
    }
    CHECK(cut.substr(cut.size() - 3) == "...");
  }
  CHECK(ClippedText(mark, 16) == "fix it in ...");
  CHECK(ClippedText("\u00e9\u00e9\u00e9\u00e9", 6) == "\u00e9...");  // two-byte characters
}
