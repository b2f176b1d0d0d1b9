// The drive train's section (models/drivetrain.h).
#include "params/parameter_file.h"
#include "params/parameter_sections.h"

namespace driveid {

DRIVEID_PARAMETER_SECTION(drive_train_section) {
  return MakeSection(DriveTrainParameterTable, "seed 000 section 4; docs/models.md#drive-train");
}

}  // namespace driveid
