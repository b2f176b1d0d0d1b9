// MAT files (v5 and v7.3), read by libmatio in the reader process
// driveid-mat-reader (logs/formats/mat_reader.h): vector variables are columns,
// matrices give their columns `name(:,k)` and rows `name(k,:)` (the longer
// side listed), struct fields are reached by dotted paths, 1 x 1 numbers and
// elements `name(i)`, `name(i,j)` are scalars for expressions.
// Cells, characters, sparse, objects and function handles are skipped with a
// note. matio reads from a file: the bytes already read (and hashed) are
// written to an unnamed temporary file first, so the data read is the data
// recorded, and a FIFO works too; the copy has no name (nothing is left
// behind by a killed process, nothing is swept).
#include "logs/formats/mat_source.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include <fcntl.h>
#include <unistd.h>
#include <sys/stat.h>

#include <fmt/format.h>

#include "core/errors.h"
#include "system/child_process.h"
#include "logs/formats/hdf5_length_check.h"
#include "logs/formats/mat_reply.h"
#include "logs/log_format.h"
#include "logs/table_source.h"
#include "system/temporary_files.h"

namespace driveid {
namespace {

std::atomic<MatReaderInChild> mat_reader_in_child{nullptr};  // ReadMatFilesInForkedChild

// The reader process (logs/formats/mat_reader.h): beside the running tool (the build
// tree's apps/, an installation's bin/ when built so), in the installation's
// libexec/driveid, or where this build made it.
std::string MatReaderPath() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  std::vector<std::filesystem::path> candidates;
  if (!error) {
    candidates.push_back(self.parent_path() / "driveid-mat-reader");
    candidates.push_back(self.parent_path().parent_path() / "libexec" / "driveid" / "driveid-mat-reader");
  }
  candidates.emplace_back(DRIVEID_MAT_READER_INSTALLED);
  for (const auto& candidate : candidates) {
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return DRIVEID_MAT_READER_BUILT;
}

// An unnamed file (system/temporary_files.h) holding `text`; -1 when none.
int UnnamedCopy(const std::string& text) {
  const int fd = CreateUnnamedFile();
  if (fd >= 0 && !WriteAll(fd, text.data(), text.size())) {
    ::close(fd);
    return -1;
  }
  return fd;
}

struct ColumnRef {
  std::string name;
  std::size_t variable = 0;
  std::size_t offset = 0, stride = 1, length = 0;
};

class MatSource : public TableSource {
 public:
  MatSource(std::string path, const std::string& text) : path_(std::move(path)) {
    // The bytes go to an unnamed file for matio, which the reader opens
    // through /proc/self/fd (matio and HDF5 open files by name).
    const int fd = UnnamedCopy(text);
    if (fd < 0) throw InputError(fmt::format("{}: cannot create a temporary copy for the MAT reader", path_));
    try {
      Load(fd, text);
    } catch (...) {
      ::close(fd);
      throw;
    }
    ::close(fd);
    // Listed columns: vectors, and each matrix along its longer side (the
    // samples): the columns name(:,k) of a tall one, the rows name(k,:) of
    // a wide one. The other side is found on request (Find).
    for (std::size_t v = 0; v < variables_.size(); ++v) {
      const MatVariable& var = variables_[v];
      if (var.rows == 1 && var.cols == 1) continue;  // a scalar
      if (var.rows == 1 || var.cols == 1) {
        columns_.push_back({var.name, v, 0, 1, var.rows * var.cols});
      } else if (var.rows >= var.cols) {
        for (std::size_t k = 0; k < var.cols; ++k) columns_.push_back(MatrixColumn(v, k + 1));
      } else {
        for (std::size_t k = 0; k < var.rows; ++k) columns_.push_back(MatrixRow(v, k + 1));
      }
    }
    listed_ = columns_.size();
    std::vector<std::string> scalars;
    for (const auto& var : variables_) {
      if (var.rows == 1 && var.cols == 1 && scalars.size() < 40) scalars.push_back(fmt::format("{} = {:.6g}", var.name, var.data[0]));
    }
    if (!scalars.empty()) notes_.push_back(fmt::format("scalars (for expressions): {}", fmt::join(scalars, ", ")));
    if (columns_.empty()) {
      throw InputError(fmt::format("{}: the MAT file has no numeric vector or matrix variable{}", path_,
                                   notes_.empty() ? "" : fmt::format(" ({})", fmt::join(notes_, "; "))));
    }
  }

  std::string path() const override { return path_; }
  std::string format() const override { return "mat"; }
  std::vector<std::string> column_names() const override {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < listed_; ++i) names.push_back(columns_[i].name);
    return names;
  }
  std::vector<std::size_t> column_lengths() const override {
    std::vector<std::size_t> lengths;
    for (std::size_t i = 0; i < listed_; ++i) lengths.push_back(columns_[i].length);
    return lengths;
  }
  // A 1 x 1 variable, or one element of a vector or matrix: name(i) (in
  // MATLAB's column-major order) or name(i,j), 1-based.
  std::optional<double> scalar(const std::string& name) const override {
    for (const auto& v : variables_) {
      if (v.name == name && v.rows == 1 && v.cols == 1) return v.data[0];
    }
    const std::size_t open = name.rfind('(');
    if (open == std::string::npos || name.back() != ')') return std::nullopt;
    const std::string inside = name.substr(open + 1, name.size() - open - 2);
    const std::size_t comma = inside.find(',');
    const auto first = Index(inside.substr(0, comma));
    const auto second = comma == std::string::npos ? std::optional<std::size_t>{1} : Index(inside.substr(comma + 1));
    if (!first || !second) return std::nullopt;
    for (const auto& v : variables_) {
      if (v.name != name.substr(0, open)) continue;
      if (comma == std::string::npos) {
        if (*first <= v.data.size()) return v.data[*first - 1];
      } else if (*first <= v.rows && *second <= v.cols) {
        return v.data[(*second - 1) * v.rows + (*first - 1)];
      }
    }
    return std::nullopt;
  }

  std::vector<SourceVariable> variables() const override {
    std::vector<SourceVariable> out;
    for (const auto& v : variables_) {
      SourceVariable entry{v.name, v.rows, v.cols, ""};
      if (v.rows == 1 && v.cols == 1) {
        entry.address = fmt::format("{} = {:.6g} (a scalar for expressions)", v.name, v.data[0]);
      } else if (v.rows == 1 || v.cols == 1) {
        entry.address = fmt::format("{} (elements {}(i) for expressions)", v.name, v.name);
      } else if (v.rows >= v.cols) {
        entry.address = fmt::format("columns {}(:,1) .. {}(:,{}); rows {}(k,:)", v.name, v.name, v.cols, v.name);
      } else {
        entry.address = fmt::format("rows {}(1,:) .. {}({},:); columns {}(:,k)", v.name, v.name, v.rows, v.name);
      }
      out.push_back(std::move(entry));
    }
    return out;
  }
  std::vector<std::string> notes() const override { return notes_; }
  // Without --col t=..., a variable `t` or else `time` is the time base.
  std::string DefaultReference(const std::string& logical) const override {
    if (logical == "t" && !TableSource::Find("t") && TableSource::Find("time")) return "time";
    return {};
  }

  std::optional<std::size_t> Find(const std::string& reference) const override {
    if (auto found = TableSource::Find(reference)) return found;
    // name(k,:) or name(:,k): the side of a matrix not listed, added on first use.
    const std::size_t open = reference.rfind('(');
    if (open == std::string::npos || reference.back() != ')') return std::nullopt;
    const std::string inside = reference.substr(open + 1, reference.size() - open - 2);
    const bool row = inside.size() > 2 && inside.compare(inside.size() - 2, 2, ",:") == 0;
    const bool column = inside.size() > 2 && inside.compare(0, 2, ":,") == 0;
    if (!row && !column) return std::nullopt;
    const auto k = Index(row ? inside.substr(0, inside.size() - 2) : inside.substr(2));
    if (!k) return std::nullopt;
    for (std::size_t v = 0; v < variables_.size(); ++v) {
      const MatVariable& var = variables_[v];
      if (var.name != reference.substr(0, open) || var.rows < 2 || var.cols < 2) continue;
      if (*k > (row ? var.rows : var.cols)) continue;
      for (std::size_t i = listed_; i < columns_.size(); ++i) {
        if (columns_[i].name == reference) return i;
      }
      columns_.push_back(row ? MatrixRow(v, *k) : MatrixColumn(v, *k));
      return columns_.size() - 1;
    }
    return std::nullopt;
  }

  TableData Read(const std::vector<std::size_t>& columns) const override {
    TableData out;
    for (auto c : columns) {
      const ColumnRef& ref = columns_.at(c);
      const MatVariable& var = variables_[ref.variable];
      std::vector<double> values(ref.length);
      for (std::size_t i = 0; i < ref.length; ++i) {
        const double v = var.data[ref.offset + i * ref.stride];
        if (!std::isfinite(v)) {
          throw InputError(fmt::format("{}: variable {}: element {} is not a finite number ({})", path_, ref.name,
                                       i + 1, v));
        }
        values[i] = v;
      }
      out.columns.push_back(std::move(values));
    }
    return out;
  }

 private:
  // matio (and HDF5 below it) trust the sizes a file claims: a corrupt file
  // can make them allocate terabytes or crash. They run in a child process,
  // the reader executable (so the tools do not map them at all otherwise)
  // (address space capped where no sanitizer needs it; time capped at 5 s
  // plus 1 s per 10 MB of file, at most 120 s); the
  // variables come back through a pipe, and a child that dies is an
  // unreadable file, not a dead tool.
  void Load(int copy, const std::string& text) {
    CheckHdf5Length(path_, text);  // a cut v7.3 file is refused without a process
    const std::string file = fmt::format("/proc/self/fd/{}", copy);
    const std::string reader = MatReaderPath();
    const char* arguments[] = {reader.c_str(), path_.c_str(), file.c_str(), nullptr};
    ChildLimits limits;
    // 1 GiB for the process itself plus three copies of what the file could
    // inflate to, at most three copies of the element cap.
    const double budget = 3.0 * (1100.0 * static_cast<double>(text.size()) + 4096.0);
    limits.address_space_bytes = static_cast<double>(1 << 30) + std::min(budget, 3.0 * 8.0 * static_cast<double>(kMaxMatElements));
    limits.seconds = std::min<long>(120, 5 + static_cast<long>(text.size() / 10'000'000));
    limits.max_output_bytes = kMaxMatElements * 8 + (std::size_t{64} << 20);
    const ChildOutcome outcome = RunInChild(
        [&] {
          // A program that links the reader (the fuzzers): the forked child reads the file itself.
          if (const MatReaderInChild in_child = mat_reader_in_child.load()) {
            ::_exit(in_child(STDOUT_FILENO, path_, file) ? 0 : 1);
          }
          ::fcntl(copy, F_SETFD, 0);  // the reader inherits the copy (this process's flag only)
          ::execv(reader.c_str(), const_cast<char* const*>(arguments));
          // Not started: say so through the pipe.
          const std::string message = SerialiseMatError(fmt::format(
              "{}: cannot start the MAT reader {} ({}): reinstall driveid (it lives beside the tools or in "
              "libexec/driveid)",
              path_, reader, std::strerror(errno)));
          WriteAll(STDOUT_FILENO, message.data(), message.size());
        },
        limits);
    if (!outcome.started) throw InputError(fmt::format("{}: cannot start the MAT reader", path_));
    if (outcome.timed_out) {
      throw InputError(fmt::format("{}: the MAT reader took longer than {} s (a corrupt file?)", path_, limits.seconds));
    }
    if (!outcome.exited || outcome.exit_code != 0 || outcome.output.empty()) {
      throw InputError(fmt::format("{}: not a readable MAT file (the reader {})", path_,
                                   outcome.signal != 0 ? fmt::format("died of signal {}", outcome.signal) : "failed"));
    }
    const std::string& reply = outcome.output;
    MatContents contents = DeserialiseMatReply(path_, reply);
    variables_ = std::move(contents.variables);
    notes_ = std::move(contents.notes);
  }

  // A 1-based index written in a reference ("12"), or nullopt.
  static std::optional<std::size_t> Index(const std::string& text) {
    std::size_t k = 0;
    const char* end = text.data() + text.size();
    const auto result = std::from_chars(text.data(), end, k);
    if (result.ec != std::errc() || result.ptr != end || k == 0) return std::nullopt;
    return k;
  }
  ColumnRef MatrixColumn(std::size_t v, std::size_t k) const {
    const MatVariable& var = variables_[v];
    return {fmt::format("{}(:,{})", var.name, k), v, (k - 1) * var.rows, 1, var.rows};
  }
  ColumnRef MatrixRow(std::size_t v, std::size_t k) const {
    const MatVariable& var = variables_[v];
    return {fmt::format("{}({},:)", var.name, k), v, k - 1, var.rows, var.cols};
  }

  std::string path_;
  std::vector<MatVariable> variables_;
  mutable std::vector<ColumnRef> columns_;  // listed ones first, then rows asked for
  std::size_t listed_ = 0;
  std::vector<std::string> notes_;
};

}  // namespace

std::unique_ptr<TableSource> OpenMatSource(const std::string& path, const std::string& text) {
  return std::make_unique<MatSource>(path, text);
}

void ReadMatFilesInForkedChild(MatReaderInChild reader) { mat_reader_in_child.store(reader); }

namespace {

constexpr std::string_view kHdf5Magic("\x89HDF\r\n\x1a\n", 8);

// A MAT file: v5 and v7.3 start with a 116-byte text header "MATLAB 5.0
// MAT-file" / "MATLAB 7.3 MAT-file" (128 bytes with the subsystem and
// version); a bare HDF5 file is taken here to be refused as one.
bool LooksLikeMat(std::string_view text) {
  return (text.size() >= 128 && (text.substr(0, 10) == "MATLAB 5.0" || text.substr(0, 10) == "MATLAB 7.3")) ||
         text.substr(0, kHdf5Magic.size()) == kHdf5Magic;
}

}  // namespace

DRIVEID_LOG_FORMAT(mat_source) {
  LogFormat format;
  format.name = "mat";
  format.source = "mat";
  format.kind = "a MAT file";
  format.sniff = LooksLikeMat;
  format.structured = true;
  format.open = [](const std::string& path, const std::string& text, const CsvFormat&, const LogSelection&) {
    if (std::string_view(text).substr(0, kHdf5Magic.size()) == kHdf5Magic) {
      throw InputError(fmt::format("{}: an HDF5 file without a MAT header: not a MAT v7.3 file", path));
    }
    std::vector<std::unique_ptr<TableSource>> out;
    out.push_back(OpenMatSource(path, text));
    return out;
  };
  return format;
}

}  // namespace driveid
