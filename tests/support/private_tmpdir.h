// A temporary folder of one test's own, made the process's TMPDIR while it
// lives (children inherit it): a test that lists the temporary folder to
// show it creates nothing there must not see what the tests ctest runs
// beside it create and remove in the shared one.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace driveid::testing {

class PrivateTmpdir {
 public:
  PrivateTmpdir() {
    path_ = std::filesystem::temp_directory_path().string() + "/driveid-test.XXXXXX";
    if (::mkdtemp(path_.data()) == nullptr) throw std::runtime_error("PrivateTmpdir: mkdtemp failed");
    const char* old = std::getenv("TMPDIR");
    had_old_ = old != nullptr;
    if (had_old_) old_ = old;
    ::setenv("TMPDIR", path_.c_str(), 1);
  }
  ~PrivateTmpdir() {
    if (had_old_) {
      ::setenv("TMPDIR", old_.c_str(), 1);
    } else {
      ::unsetenv("TMPDIR");
    }
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  PrivateTmpdir(const PrivateTmpdir&) = delete;
  PrivateTmpdir& operator=(const PrivateTmpdir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_, old_;
  bool had_old_ = false;
};

}  // namespace driveid::testing
