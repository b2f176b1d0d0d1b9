// The bytes of a large binary log (a ROS bag), read piece by piece: from a
// regular file with pread through a read-ahead window, so that a 1 GB bag
// is never held whole, or from bytes already in memory (tests, fuzzers).
// Every range asked for is checked against the size first.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace driveid {

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  /// The name errors give (the file's path).
  virtual const std::string& name() const = 0;
  /// The size [bytes].
  virtual std::uint64_t size() const = 0;
  /// Bytes [offset, offset + length): valid until the next call; InputError
  /// naming the file and offset when they lie beyond its end.
  virtual std::string_view View(std::uint64_t offset, std::uint64_t length) = 0;
  /// The whole content when it is in memory, else nullptr.
  virtual const std::string* memory() const { return nullptr; }
  /// InputError when the file changed (size or modification time) since it
  /// was opened: what was parsed must be what was hashed.
  virtual void CheckUnchanged() const {}
};

/// `bytes` (which must outlive the source) as a source named `name`.
std::unique_ptr<ByteSource> MemoryBytes(const std::string& name, const std::string& bytes);

/// The regular file `path`, opened for reading piece by piece; nullptr when
/// it is no regular file (a FIFO, a device), InputError when it cannot be
/// opened.
std::unique_ptr<ByteSource> OpenFileBytes(const std::string& path);

}  // namespace driveid
