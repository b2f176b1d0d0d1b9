// The elastic joint's section (models/joint.h).
#include "params/parameter_file.h"
#include "params/parameter_sections.h"

namespace driveid {

DRIVEID_PARAMETER_SECTION(joint_section) {
  return MakeSection(JointParameterTable, "docs/models.md#elastic-joint: two masses, link side");
}

}  // namespace driveid
