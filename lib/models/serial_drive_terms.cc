// The serial arm's drive terms, registered in the regressor's and the
// parameter file's order (models/serial_drive_term.h). The list is
// DRIVEID_SERIAL_DRIVE_TERMS in lib/CMakeLists.txt.
#include <memory>
#include <stdexcept>

#include "core/registered_objects.h"
#include "models/serial_drive_term.h"

namespace driveid {

#define DRIVEID_REGISTERED_SERIAL_DRIVE_TERM(name) std::unique_ptr<SerialDriveTerm> MakeSerialDriveTerm_##name();
#include "models/registered_serial_drive_terms.inc"
#undef DRIVEID_REGISTERED_SERIAL_DRIVE_TERM

namespace {

using MakeTerm = std::unique_ptr<SerialDriveTerm> (*)();
#define DRIVEID_REGISTERED_SERIAL_DRIVE_TERM(name) MakeSerialDriveTerm_##name,
const MakeTerm kRegistered[] = {
#include "models/registered_serial_drive_terms.inc"
};
#undef DRIVEID_REGISTERED_SERIAL_DRIVE_TERM

RegisteredObjects<SerialDriveTerm> Build() {
  RegisteredObjects<SerialDriveTerm> r = MakeRegisteredObjects(kRegistered);
  if (r.list.size() != kSerialDriveTerms) {
    throw std::logic_error("serial drive terms: the registered terms do not match kSerialDriveTerms");
  }
  return r;
}

}  // namespace

const std::vector<const SerialDriveTerm*>& SerialDriveTerms() {
  static const RegisteredObjects<SerialDriveTerm> registry = Build();
  return registry.list;
}

}  // namespace driveid
