#include "logs/formats/mat_reply.h"

#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

std::string SerialiseMatReply(const MatContents& contents) {
  std::string out(1, '\0');
  const auto put = [&](std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
  const auto put_text = [&](const std::string& s) {
    put(s.size());
    out += s;
  };
  put(contents.variables.size());
  for (const auto& v : contents.variables) {
    put_text(v.name);
    put(v.rows);
    put(v.cols);
    out.append(reinterpret_cast<const char*>(v.data.data()), v.data.size() * sizeof(double));
  }
  put(contents.notes.size());
  for (const auto& n : contents.notes) put_text(n);
  return out;
}

std::string SerialiseMatError(const std::string& message) { return std::string(1, '\1') + message; }

MatContents DeserialiseMatReply(const std::string& path, const std::string& in) {
  if (in.empty()) throw InputError(fmt::format("{}: the MAT reader's reply is empty", path));
  if (in[0] == '\1') throw InputError(in.substr(1));
  MatContents out;
  std::size_t at = 1;
  const auto get = [&]() {
    std::uint64_t v = 0;
    if (in.size() - at < sizeof v) throw InputError(fmt::format("{}: the MAT reader's reply is cut short", path));
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  };
  const auto get_bytes = [&](std::uint64_t n) {
    if (in.size() - at < n) throw InputError(fmt::format("{}: the MAT reader's reply is cut short", path));
    std::string s = in.substr(at, n);
    at += n;
    return s;
  };
  const std::uint64_t count = get();
  for (std::uint64_t i = 0; i < count; ++i) {
    MatVariable v;
    v.name = get_bytes(get());
    v.rows = get();
    v.cols = get();
    if (v.cols != 0 && v.rows > kMaxMatElements / v.cols) throw InputError(fmt::format("{}: variable too large", path));
    const std::string bytes = get_bytes(v.rows * v.cols * sizeof(double));
    v.data.resize(v.rows * v.cols);
    if (!bytes.empty()) std::memcpy(v.data.data(), bytes.data(), bytes.size());  // (an empty vector's data() may be null)
    out.variables.push_back(std::move(v));
  }
  const std::uint64_t notes = get();
  for (std::uint64_t i = 0; i < notes; ++i) out.notes.push_back(get_bytes(get()));
  return out;
}

}  // namespace driveid
