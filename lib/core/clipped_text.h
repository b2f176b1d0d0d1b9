// A message cut to a length for another message: never inside a UTF-8
// character (the option marks ‹ › are three bytes each) nor inside an
// option mark, ending in "..." where it was cut. (A cut "‹params›" reached
// users as "fix it in ‹pa))".)
#pragma once

#include <cstddef>
#include <string>

namespace driveid {

/// `text` whole when at most `bytes` long, else its longest prefix of at
/// most `bytes - 3` bytes that ends neither inside a UTF-8 sequence nor
/// inside a ‹...› mark, followed by "...".
inline std::string ClippedText(const std::string& text, std::size_t bytes) {
  if (text.size() <= bytes) return text;
  std::size_t end = bytes > 3 ? bytes - 3 : 0;
  // Back to the start of a character: continuation bytes are 10xxxxxx.
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
  // Not inside a mark: an opening ‹ after the last closing › is cut off.
  const std::string open = "\u2039", close = "\u203A";
  const std::size_t opened = text.rfind(open, end == 0 ? 0 : end - 1);
  const std::size_t closed = text.rfind(close, end == 0 ? 0 : end - 1);
  if (opened != std::string::npos && opened < end && (closed == std::string::npos || closed < opened)) end = opened;
  return text.substr(0, end) + "...";
}

}  // namespace driveid
