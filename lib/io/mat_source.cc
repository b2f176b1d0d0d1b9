// MAT files (v5 and v7.3) through libmatio: vector variables are columns,
// matrices give their columns `name(:,k)` and rows `name(k,:)` (the longer
// side listed), struct fields are reached by dotted paths, 1 x 1 numbers and
// elements `name(i)`, `name(i,j)` are scalars for expressions.
// Cells, characters, sparse, objects and function handles are skipped with a
// note. matio reads from a file: the bytes already read (and hashed) are
// written to a registered temporary file first, so the data read is the data
// recorded, and a FIFO works too.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <matio.h>

#include "core/errors.h"
#include "io/hdf5_storage_check.h"
#include "io/mat_structure_check.h"
#include "io/table_source.h"
#include "io/temporary_files.h"

// AddressSanitizer reserves its shadow memory up front: an address-space
// cap would make every allocation fail, so the cap is left out there.
#if defined(__SANITIZE_ADDRESS__)
#define DRIVEID_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DRIVEID_ASAN 1
#endif
#endif

namespace driveid {
namespace {

// matio logs through a global function: keep its last message for ours
// (the library prints nothing).
std::mutex log_mutex;
std::string last_matio_message;

void CaptureMatioLog(int, char* message) {
  if (message != nullptr) last_matio_message = message;
}

// Elements one file may expand to (2 GiB of doubles): a compressed variable
// can claim far more than its bytes.
constexpr std::size_t kMaxElements = std::size_t{1} << 28;
constexpr std::size_t kMaxVariables = 100000;  // top-level variables of one file

struct Variable {
  std::string name;  // dotted path
  std::size_t rows = 0, cols = 0;
  std::vector<double> data;  // column-major
};

struct ColumnRef {
  std::string name;
  std::size_t variable = 0;
  std::size_t offset = 0, stride = 1, length = 0;
};

template <typename T>
void Convert(const void* data, std::size_t n, std::vector<double>& out) {
  const T* p = static_cast<const T*>(data);
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(p[i]);
}

bool ConvertNumeric(const matvar_t* v, std::size_t n, std::vector<double>& out) {
  if (v->data == nullptr) return false;
  switch (v->class_type) {
    case MAT_C_DOUBLE: Convert<double>(v->data, n, out); return true;
    case MAT_C_SINGLE: Convert<float>(v->data, n, out); return true;
    case MAT_C_INT8: Convert<std::int8_t>(v->data, n, out); return true;
    case MAT_C_UINT8: Convert<std::uint8_t>(v->data, n, out); return true;
    case MAT_C_INT16: Convert<std::int16_t>(v->data, n, out); return true;
    case MAT_C_UINT16: Convert<std::uint16_t>(v->data, n, out); return true;
    case MAT_C_INT32: Convert<std::int32_t>(v->data, n, out); return true;
    case MAT_C_UINT32: Convert<std::uint32_t>(v->data, n, out); return true;
    case MAT_C_INT64: Convert<std::int64_t>(v->data, n, out); return true;
    case MAT_C_UINT64: Convert<std::uint64_t>(v->data, n, out); return true;
    default: return false;
  }
}

// The bytes a variable's header claims (dimensions × element size), summed
// over struct fields and cells; overflow and absurd ranks count as infinite.
double ClaimedBytes(matvar_t* var, int depth) {
  if (var == nullptr) return 0.0;
  if (depth > 16 || var->rank < 0 || var->rank > 32 || (var->rank > 0 && var->dims == nullptr)) return HUGE_VAL;
  double elements = 1.0;
  for (int k = 0; k < var->rank; ++k) elements *= static_cast<double>(var->dims[k]);
  if (var->class_type == MAT_C_STRUCT) {
    const unsigned fields = Mat_VarGetNumberOfFields(var);
    double total = 64.0 * elements * fields;
    if (elements > 1e6 || var->data == nullptr) return total;
    for (std::size_t i = 0; i < static_cast<std::size_t>(elements) && total < HUGE_VAL; ++i) {
      for (unsigned f = 0; f < fields; ++f) total += ClaimedBytes(Mat_VarGetStructFieldByIndex(var, f, i), depth + 1);
    }
    return total;
  }
  if (var->class_type == MAT_C_CELL) {
    double total = 64.0 * elements;
    if (elements > 1e6 || var->data == nullptr) return total;
    for (std::size_t i = 0; i < static_cast<std::size_t>(elements) && total < HUGE_VAL; ++i) {
      total += ClaimedBytes(Mat_VarGetCell(var, static_cast<int>(i)), depth + 1);
    }
    return total;
  }
  const double size = static_cast<double>(std::max<std::size_t>(Mat_SizeOfClass(var->class_type), 1));
  return elements * size * (var->isComplex ? 2.0 : 1.0);
}

const char* ClassName(matio_classes c) {
  switch (c) {
    case MAT_C_CELL: return "cell array";
    case MAT_C_STRUCT: return "struct array";
    case MAT_C_OBJECT: return "object";
    case MAT_C_CHAR: return "text";
    case MAT_C_SPARSE: return "sparse matrix";
    case MAT_C_FUNCTION: return "function handle";
    case MAT_C_OPAQUE: return "opaque object";
    case MAT_C_EMPTY: return "empty array";
    default: return "numeric";
  }
}

class MatSource : public TableSource {
 public:
  MatSource(std::string path, const std::string& text) : path_(std::move(path)) {
    CheckHdf5Length(path_, text);
    // The bytes go to a temporary file for matio.
    std::string name = (std::filesystem::temp_directory_path() / "driveid-mat.tmp.XXXXXX").string();
    const int fd = CreateTemporaryFile(name);
    if (fd < 0) throw InputError(fmt::format("{}: cannot create a temporary copy for the MAT reader", path_));
    std::size_t written = 0;
    bool ok = true;
    while (written < text.size()) {
      const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
      if (n <= 0) {
        ok = false;
        break;
      }
      written += static_cast<std::size_t>(n);
    }
    ::close(fd);
    try {
      if (!ok) throw InputError(fmt::format("{}: cannot write a temporary copy for the MAT reader", path_));
      Load(name, text);
    } catch (...) {
      RemoveTemporaryFile(name);
      throw;
    }
    RemoveTemporaryFile(name);
    // Listed columns: vectors, and each matrix along its longer side (the
    // samples): the columns name(:,k) of a tall one, the rows name(k,:) of
    // a wide one. The other side is found on request (Find).
    for (std::size_t v = 0; v < variables_.size(); ++v) {
      const Variable& var = variables_[v];
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
      const Variable& var = variables_[v];
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
      const Variable& var = variables_[ref.variable];
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
  // can make them allocate terabytes or crash. They run in a child process
  // (address space capped where no sanitizer needs it; time capped at 5 s
  // plus 1 s per 10 MB of file, at most 120 s); the
  // variables come back through a pipe, and a child that dies is an
  // unreadable file, not a dead tool.
  void Load(const std::string& file, const std::string& text) {
    const std::size_t text_size = text.size();
    int fds[2];
    if (::pipe(fds) != 0) throw InputError(fmt::format("{}: cannot start the MAT reader", path_));
    const pid_t parent = ::getpid();
    const pid_t child = ::fork();
    if (child < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      throw InputError(fmt::format("{}: cannot start the MAT reader", path_));
    }
    if (child == 0) {
      // The reader dies with the tool, however the tool ends (SIGKILL too).
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(1);
      ::close(fds[0]);
#if !defined(DRIVEID_ASAN)
      // 1 GiB for the process itself plus three copies of what the file
      // could inflate to, at most three copies of the element cap.
      const double budget = 3.0 * (1100.0 * static_cast<double>(text_size) + 4096.0);
      const rlim_t cap = (rlim_t{1} << 30) +
                         static_cast<rlim_t>(std::min(budget, 3.0 * 8.0 * static_cast<double>(kMaxElements)));
      const struct rlimit limit = {cap, cap};
      ::setrlimit(RLIMIT_AS, &limit);
#endif
      std::string message;
      try {
        CheckMatV5Elements(path_, text);
        CheckHdf5Storage(path_, file);
        LoadHere(file);
        message = Serialise();
      } catch (const std::exception& e) {
        message = std::string(1, '\1') + e.what();
      } catch (...) {
        message = std::string(1, '\1') + "the MAT reader failed";
      }
      std::size_t written = 0;
      while (written < message.size()) {
        const ssize_t n = ::write(fds[1], message.data() + written, message.size() - written);
        if (n <= 0) break;
        written += static_cast<std::size_t>(n);
      }
      ::_exit(written == message.size() ? 0 : 1);
    }
    ::close(fds[1]);
    SetTemporaryFileWriter(child);  // killed by the tools' signal handlers
    std::string reply;
    std::vector<char> chunk(1 << 16);
    const long seconds_allowed = std::min<long>(120, 5 + static_cast<long>(text_size / 10'000'000));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds_allowed);
    bool timed_out = false;
    while (true) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) {
        timed_out = true;
        break;
      }
      struct pollfd p = {fds[0], POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
      if (ready < 0 && errno == EINTR) continue;
      if (ready <= 0) {
        timed_out = ready == 0;
        break;
      }
      const ssize_t n = ::read(fds[0], chunk.data(), chunk.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      reply.append(chunk.data(), static_cast<std::size_t>(n));
      if (reply.size() > kMaxElements * 8 + (std::size_t{64} << 20)) break;
    }
    ::close(fds[0]);
    if (timed_out) ::kill(child, SIGKILL);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    SetTemporaryFileWriter(0);
    if (timed_out) {
      throw InputError(fmt::format("{}: the MAT reader took longer than {} s (a corrupt file?)", path_, seconds_allowed));
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || reply.empty()) {
      throw InputError(fmt::format("{}: not a readable MAT file (the reader {})", path_,
                                   WIFSIGNALED(status) ? fmt::format("died of signal {}", WTERMSIG(status))
                                                       : "failed"));
    }
    if (reply[0] == '\1') throw InputError(reply.substr(1));
    Deserialise(reply);
  }

  // The reply: 0, then per variable its name, rows, cols and values, then the notes.
  std::string Serialise() const {
    std::string out(1, '\0');
    const auto put = [&](std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
    const auto put_text = [&](const std::string& s) {
      put(s.size());
      out += s;
    };
    put(variables_.size());
    for (const auto& v : variables_) {
      put_text(v.name);
      put(v.rows);
      put(v.cols);
      out.append(reinterpret_cast<const char*>(v.data.data()), v.data.size() * sizeof(double));
    }
    put(notes_.size());
    for (const auto& n : notes_) put_text(n);
    return out;
  }

  void Deserialise(const std::string& in) {
    std::size_t at = 1;
    const auto get = [&]() {
      std::uint64_t v = 0;
      if (in.size() - at < sizeof v) throw InputError(fmt::format("{}: the MAT reader's reply is cut short", path_));
      std::memcpy(&v, in.data() + at, sizeof v);
      at += sizeof v;
      return v;
    };
    const auto get_bytes = [&](std::uint64_t n) {
      if (in.size() - at < n) throw InputError(fmt::format("{}: the MAT reader's reply is cut short", path_));
      std::string s = in.substr(at, n);
      at += n;
      return s;
    };
    const std::uint64_t count = get();
    for (std::uint64_t i = 0; i < count; ++i) {
      Variable v;
      v.name = get_bytes(get());
      v.rows = get();
      v.cols = get();
      if (v.cols != 0 && v.rows > kMaxElements / v.cols) throw InputError(fmt::format("{}: variable too large", path_));
      const std::string bytes = get_bytes(v.rows * v.cols * sizeof(double));
      v.data.resize(v.rows * v.cols);
      std::memcpy(v.data.data(), bytes.data(), bytes.size());
      variables_.push_back(std::move(v));
    }
    const std::uint64_t notes = get();
    for (std::uint64_t i = 0; i < notes; ++i) notes_.push_back(get_bytes(get()));
  }

  void LoadHere(const std::string& file) {
    std::lock_guard<std::mutex> lock(log_mutex);
    Mat_LogInitFunc("driveid", CaptureMatioLog);
    last_matio_message.clear();
    mat_t* mat = Mat_Open(file.c_str(), MAT_ACC_RDONLY);
    if (mat == nullptr) {
      throw InputError(fmt::format("{}: not a readable MAT file{}", path_,
                                   last_matio_message.empty() ? "" : ": " + last_matio_message));
    }
    // Sizes claimed in the headers are checked before anything is read: a
    // variable cannot hold more bytes than the file could inflate to (zlib
    // expands at most ~1032-fold), so a hostile header never makes matio
    // allocate gigabytes.
    std::error_code error;
    const std::uintmax_t file_size = std::filesystem::file_size(file, error);
    const double byte_budget = 1100.0 * static_cast<double>(error ? 0 : file_size) + 4096.0;
    // First pass: headers only. Second pass in the same order: each
    // variable read in turn (Mat_VarRead by name rescans the file from the
    // start: quadratic in the number of variables), the refused ones skipped
    // by their headers.
    std::vector<bool> wanted;
    std::size_t variables = 0;
    while (matvar_t* info = Mat_VarReadNextInfo(mat)) {
      bool ok = false;
      if (info->name != nullptr) {
        if (++variables > kMaxVariables) {
          Mat_VarFree(info);
          Mat_Close(mat);
          throw InputError(fmt::format("{}: more than {} variables: a log file holds at most {}", path_, kMaxVariables,
                                       kMaxVariables));
        }
        const double claimed = ClaimedBytes(info, 0);
        ok = claimed <= byte_budget && claimed <= 8.0 * static_cast<double>(kMaxElements);
        if (!ok) {
          notes_.push_back(fmt::format("{}: skipped (its header claims {:.3g} bytes in a file of {} bytes)", info->name,
                                       claimed, file_size));
        }
      }
      wanted.push_back(ok);
      Mat_VarFree(info);
    }
    std::size_t elements = 0;
    try {
      if (Mat_Rewind(mat) != 0) throw InputError(fmt::format("{}: not a readable MAT file (cannot rewind)", path_));
      for (std::size_t index = 0; index < wanted.size(); ++index) {
        if (!wanted[index]) {
          if (matvar_t* info = Mat_VarReadNextInfo(mat)) Mat_VarFree(info);
          continue;
        }
        matvar_t* var = Mat_VarReadNext(mat);
        if (var == nullptr) {
          notes_.push_back(fmt::format("variable {}: skipped (matio cannot read it{})", index + 1,
                                       last_matio_message.empty() ? "" : ": " + last_matio_message));
          continue;
        }
        const std::string name = var->name != nullptr ? var->name : "";
        try {
          Add(var, name, 0, elements);
        } catch (...) {
          Mat_VarFree(var);
          throw;
        }
        Mat_VarFree(var);
      }
    } catch (...) {
      Mat_Close(mat);
      throw;
    }
    Mat_Close(mat);
  }

  void Add(matvar_t* var, const std::string& name, int depth, std::size_t& elements) {
    if (var->rank != 2 || var->dims == nullptr) {
      notes_.push_back(fmt::format("{}: skipped ({}-dimensional)", name, var->rank));
      return;
    }
    const std::size_t rows = var->dims[0], cols = var->dims[1];
    if (var->class_type == MAT_C_STRUCT) {
      if (rows * cols != 1 || depth > 16) {
        notes_.push_back(fmt::format("{}: skipped (struct array {} x {}; give one struct)", name, rows, cols));
        return;
      }
      const unsigned count = Mat_VarGetNumberOfFields(var);
      char* const* fields = Mat_VarGetStructFieldnames(var);
      for (unsigned f = 0; f < count && fields != nullptr; ++f) {
        matvar_t* field = Mat_VarGetStructFieldByIndex(var, f, 0);
        if (field != nullptr && fields[f] != nullptr) Add(field, name + "." + fields[f], depth + 1, elements);
      }
      return;
    }
    if (var->isComplex) {
      notes_.push_back(fmt::format("{}: skipped (complex numbers)", name));
      return;
    }
    Variable v{name, rows, cols, {}};
    if (rows == 0 || cols == 0 || rows > kMaxElements / std::max<std::size_t>(cols, 1) ||
        elements + rows * cols > kMaxElements) {
      notes_.push_back(fmt::format("{}: skipped ({} x {} {})", name, rows, cols,
                                   rows == 0 || cols == 0 ? "empty" : "too large"));
      return;
    }
    if (!ConvertNumeric(var, rows * cols, v.data)) {
      notes_.push_back(fmt::format("{}: skipped ({})", name, ClassName(var->class_type)));
      return;
    }
    elements += rows * cols;
    variables_.push_back(std::move(v));
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
    const Variable& var = variables_[v];
    return {fmt::format("{}(:,{})", var.name, k), v, (k - 1) * var.rows, 1, var.rows};
  }
  ColumnRef MatrixRow(std::size_t v, std::size_t k) const {
    const Variable& var = variables_[v];
    return {fmt::format("{}({},:)", var.name, k), v, k - 1, var.rows, var.cols};
  }

  std::string path_;
  std::vector<Variable> variables_;
  mutable std::vector<ColumnRef> columns_;  // listed ones first, then rows asked for
  std::size_t listed_ = 0;
  std::vector<std::string> notes_;
};

}  // namespace

std::unique_ptr<TableSource> OpenMatSource(const std::string& path, const std::string& text) {
  return std::make_unique<MatSource>(path, text);
}

}  // namespace driveid
