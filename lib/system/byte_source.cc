#include "system/byte_source.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

void CheckRange(const std::string& name, std::uint64_t size, std::uint64_t offset, std::uint64_t length) {
  if (offset > size || length > size - offset) {
    throw InputError(fmt::format("{}: {} bytes at offset {} lie beyond its end ({} bytes)", name, length, offset, size));
  }
}

class Memory final : public ByteSource {
 public:
  Memory(const std::string& name, const std::string& bytes) : name_(name), bytes_(bytes) {}
  const std::string& name() const override { return name_; }
  std::uint64_t size() const override { return bytes_.size(); }
  std::string_view View(std::uint64_t offset, std::uint64_t length) override {
    CheckRange(name_, bytes_.size(), offset, length);
    return std::string_view(bytes_).substr(offset, length);
  }
  const std::string* memory() const override { return &bytes_; }

 private:
  std::string name_;
  const std::string& bytes_;
};

// Reads ahead in windows of kWindow bytes; a longer range gets a buffer of
// its own (a chunk, at most what the file holds).
class File final : public ByteSource {
 public:
  static constexpr std::uint64_t kWindow = std::uint64_t{4} << 20;
  File(const std::string& path, int fd, const struct stat& status) : name_(path), fd_(fd), status_(status) {}
  ~File() override { ::close(fd_); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  const std::string& name() const override { return name_; }
  std::uint64_t size() const override { return static_cast<std::uint64_t>(status_.st_size); }
  std::string_view View(std::uint64_t offset, std::uint64_t length) override {
    CheckRange(name_, size(), offset, length);
    if (offset >= window_offset_ && offset + length <= window_offset_ + window_.size()) {
      return std::string_view(window_).substr(offset - window_offset_, length);
    }
    if (length > kWindow / 2) {
      Fill(large_, offset, length);
      return large_;
    }
    Fill(window_, offset, std::min(kWindow, size() - offset));
    window_offset_ = offset;
    return std::string_view(window_).substr(0, length);
  }
  void CheckUnchanged() const override {
    struct stat now {};
    if (::fstat(fd_, &now) != 0 || now.st_size != status_.st_size || now.st_mtim.tv_sec != status_.st_mtim.tv_sec ||
        now.st_mtim.tv_nsec != status_.st_mtim.tv_nsec) {
      throw InputError(fmt::format("{}: changed while it was read (size or modification time): read it again when it "
                                   "is complete",
                                   name_));
    }
  }

 private:
  void Fill(std::string& into, std::uint64_t offset, std::uint64_t length) {
    into.resize(length);
    std::uint64_t done = 0;
    while (done < length) {
      const ssize_t got = ::pread(fd_, into.data() + done, length - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) throw InputError(fmt::format("{}: read error at offset {}: {}", name_, offset + done, std::strerror(errno)));
      if (got == 0) {
        throw InputError(fmt::format("{}: ends at offset {}, before the {} bytes it had when opened", name_,
                                     offset + done, size()));
      }
      done += static_cast<std::uint64_t>(got);
    }
  }
  std::string name_;
  int fd_;
  struct stat status_;
  std::string window_, large_;
  std::uint64_t window_offset_ = 0;
};

}  // namespace

std::unique_ptr<ByteSource> MemoryBytes(const std::string& name, const std::string& bytes) {
  return std::make_unique<Memory>(name, bytes);
}

std::unique_ptr<ByteSource> OpenFileBytes(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(fmt::format("{}: cannot open file for reading: {}", path, std::strerror(errno)));
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    ::close(fd);
    return nullptr;
  }
  return std::make_unique<File>(path, fd, status);
}

}  // namespace driveid
