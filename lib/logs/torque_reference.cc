#include "logs/torque_reference.h"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/log_input.h"
#include "logs/log_columns.h"
#include "signal/butterworth.h"

namespace driveid {
namespace {
using R = TorqueReference;
constexpr LogColumn<R> kColumns[] = {
    RequiredColumn<R>("t", &FieldOf<R, &R::time>, "{}"),
    RequiredColumn<R>("tau", &FieldOf<R, &R::torque>, "{:.12g}"),
};
constexpr std::size_t kMinRows = 16;

}  // namespace

TorqueReference ReadTorqueReference(const std::string& path) {
  CsvLog csv = ReadCsvLog(path, LogColumnRequest(kColumns));
  if (csv.rows() < kMinRows) {
    throw InputError(fmt::format("{}: {} rows: an excitation needs at least {}", path, csv.rows(), kMinRows));
  }
  TorqueReference r = MakeLogFromColumns(kColumns, csv);
  if (!(ConstantRate(r.time) > 0.0)) {
    throw InputError(fmt::format("{}: the time steps of column t are not constant (an injected excitation is "
                                 "sampled at the logging rate)",
                                 path));
  }
  return r;
}

double TorqueReferenceRate(const TorqueReference& reference) { return ConstantRate(reference.time); }

std::string FormatTorqueReference(const TorqueReference& reference, const std::vector<std::string>& comments) {
  return FormatLogColumns(kColumns, reference, comments);
}

}  // namespace driveid
