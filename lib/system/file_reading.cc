#include "system/file_reading.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <new>
#include <string_view>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

namespace {

// The descriptor of `path`, open for reading: a directory, or a regular file
// larger than the limit, is refused before a byte is read; a named FIFO is
// given `limits.fifo_wait_seconds` for a writer to send its first bytes (an
// open that waits for a writer would block forever). Anonymous pipes
// (/dev/stdin from a pipeline) have their writer already and are read as is.
int OpenForReading(const std::string& path, const ReadLimits& limits) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(fmt::format("{}: cannot open file for reading: {}", path, std::strerror(errno)));
  const auto refuse = [&](const std::string& message) {
    ::close(fd);
    throw InputError(message);
  };
  struct stat status {};
  if (::fstat(fd, &status) != 0) refuse(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
  if (S_ISDIR(status.st_mode)) refuse(fmt::format("{}: is a directory, not a file", path));
  if (S_ISREG(status.st_mode) && static_cast<std::uintmax_t>(status.st_size) > limits.max_bytes) {
    refuse(fmt::format("{}: larger than {} bytes ({})", path, limits.max_bytes, limits.max_bytes_hint));
  }
  if (S_ISFIFO(status.st_mode)) {
    std::array<char, 64> link{};
    const std::string self = fmt::format("/proc/self/fd/{}", fd);
    const ssize_t length = ::readlink(self.c_str(), link.data(), link.size() - 1);
    const bool anonymous = length > 5 && std::string_view(link.data(), 5) == "pipe:";
    if (!anonymous) {
      struct pollfd wait = {fd, POLLIN, 0};
      int ready = -1;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.fifo_wait_seconds);
      while (ready < 0 || (ready == 0 && std::chrono::steady_clock::now() < deadline)) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        ready = ::poll(&wait, 1, static_cast<int>(std::max<long long>(0, left.count())));
        if (ready < 0 && errno != EINTR) break;
        if (ready < 0) ready = 0;
      }
      if (ready <= 0) {
        refuse(fmt::format("{}: a FIFO that no process wrote to within {} s (start its writer first)", path,
                           limits.fifo_wait_seconds));
      }
    }
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

// Line-oriented input: a control byte (other than tab, CR, LF, form feed)
// means binary data (/dev/urandom, a UTF-16 export), refused where it
// appears; a line longer than `max_line_bytes` is refused too.
// `line_length` carries the open line over chunks; `lines` counts the
// newlines before `chunk`.
void CheckTextChunk(const std::string& path, std::string_view chunk, std::size_t max_line_bytes, std::size_t offset,
                    std::size_t lines, std::size_t& line_length) {
  const auto too_long = [&](std::size_t length) {
    if (length > max_line_bytes) {
      throw InputError(fmt::format("{}:{}: line longer than {} bytes", path, lines + 1, max_line_bytes));
    }
  };
  std::size_t line_start = 0;
  for (std::size_t k = 0; k < chunk.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(chunk[k]);
    if (c >= 0x20 || c == '\t' || c == '\r' || c == '\f') continue;
    if (c == '\n') {
      too_long(line_length + (k - line_start));
      ++lines;
      line_length = 0;
      line_start = k + 1;
      continue;
    }
    throw InputError(fmt::format("{}:{}: byte 0x{:02x} at offset {}: not a text file (a log is CSV text, JSON or MAT{})",
                                 path, lines + 1, c, offset + k, c == 0 ? "; a UTF-16 export? save it as UTF-8" : ""));
  }
  line_length += chunk.size() - line_start;
  too_long(line_length);
}

}  // namespace

std::string ReadFileToString(const std::string& path, const ReadLimits& limits) {
  const int fd = OpenForReading(path, limits);
  // Read in chunks with the limits enforced as the bytes arrive, so that an
  // endless input (/dev/zero, a FIFO) fails fast instead of filling memory.
  std::string text;
  std::size_t line_length = 0, lines = 0;
  std::size_t max_line_bytes = limits.max_line_bytes;
  bool first_chunk = true;
  std::vector<char> chunk(1 << 16);
  try {
    for (;;) {
      const ssize_t got = ::read(fd, chunk.data(), chunk.size());
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) throw InputError(fmt::format("{}: read error: {}", path, std::strerror(errno)));
      if (got == 0) break;
      const std::string_view piece(chunk.data(), static_cast<std::size_t>(got));
      if (text.size() + piece.size() > limits.max_bytes) {
        throw InputError(fmt::format("{}: larger than {} bytes ({})", path, limits.max_bytes, limits.max_bytes_hint));
      }
      if (first_chunk && limits.structured != nullptr && limits.structured(piece)) max_line_bytes = 0;
      if (max_line_bytes > 0) {
        CheckTextChunk(path, piece, max_line_bytes, text.size(), lines, line_length);
        lines += static_cast<std::size_t>(std::count(piece.begin(), piece.end(), '\n'));
      }
      if (first_chunk) {
        // A regular file is held whole: reserved once it looks like a log.
        struct stat status {};
        if (::fstat(fd, &status) == 0 && S_ISREG(status.st_mode) && status.st_size > 0) {
          text.reserve(static_cast<std::size_t>(status.st_size));
        }
        first_chunk = false;
      }
      text.append(piece);
    }
  } catch (const std::bad_alloc&) {
    ::close(fd);
    throw InputError(fmt::format("{}: does not fit in the memory this process may use ({} bytes read)", path,
                                 text.size()));
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return text;
}

}  // namespace driveid
