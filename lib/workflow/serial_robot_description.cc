#include "workflow/serial_robot_description.h"

#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "params/serial_robot_section.h"

namespace driveid {

RobotToIdentify ReadRobotToIdentify(const std::string& urdf_path, const std::string& params_path) {
  RobotToIdentify out;
  out.urdf_text = ReadUrdfText(urdf_path);
  out.robot = ParseUrdfRobot(urdf_path, out.urdf_text);
  if (params_path.empty()) return out;
  const ParameterFile given = ReadParameterFile(params_path);
  const RobotCouplingSection* section = given.Find<RobotCouplingSection>();
  if (section == nullptr) {
    throw OptionError(fmt::format("‹params› {}: with ‹urdf› a file with a robot section (the drives' coupling, "
                                  "docs/formats.md#the-robot-section)",
                                  params_path));
  }
  out.robot.robot = WithCoupling(std::move(out.robot.robot), given, params_path);
  out.coupling = *section;
  return out;
}

SerialRobot RobotOfParameterFile(const ParameterFile& file, const std::string& params_path,
                                 const std::string& urdf_path) {
  const SerialRobotSection* section = file.Find<SerialRobotSection>();
  if (section == nullptr) {
    throw InputError(params_path + ": no 'serial_robot' section (drivetrain-fit robot ‹urdf› -o)");
  }
  return WithCoupling(ReadSectionUrdf(*section, urdf_path, params_path).robot, file, params_path);
}

}  // namespace driveid
