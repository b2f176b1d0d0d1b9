#!/usr/bin/env bash
# drivetrain-fit export (docs/export.md): every target written from a fitted
# axis and read back by its consumer where this machine has it — check_urdf
# (Debian's liburdfdom-tools) for URDF, javac against stub classes with
# WPILib's constructor signatures for Java (WPILib is not in Debian: the
# stubs check the syntax, the class, the constructor arity and the types),
# gcc and g++ for the C header (its values printed and compared with the
# parameter file), json_check for JSON; MuJoCo loads the MJCF in
# tests/export/mjcf_mujoco_test.cc, and `validate MODEL.xml` simulates it
# in MuJoCo against driveid's own simulation of the same fit. Refusals by name.
# Usage: export_cli_test.sh DRIVETRAIN_FIT SOURCE_DIR JSON_CHECK [HAVE_MUJOCO: ON|OFF]
set -u
bin="$1"
src="$2"
json_check="$3"
have_mujoco="${4:-OFF}"
program=drivetrain-fit
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

"$bin" axis "$src/data/axis_steps.csv" -q -o axis.yaml || fail "axis fit"
for target in mjcf urdf wpilib-java c-header json; do
  "$bin" export axis.yaml --to "$target" --joint shoulder -o "out.$target" 2> stderr.txt && [ -s "out.$target" ] && ok ||
    fail "export --to $target: $(cat stderr.txt)"
done
grep -q 'frictionloss="1.00' out.mjcf && grep -q 'type="hinge"' out.mjcf && ok || fail "mjcf: $(head -c 400 out.mjcf)"
"$json_check" out.json > /dev/null && grep -q '"Ks":{"value":1.00' out.json && ok || fail "json: $(cat out.json)"

if command -v check_urdf > /dev/null; then
  check_urdf out.urdf > check.txt 2>&1 && grep -q "robot name is: driveid_shoulder" check.txt && ok ||
    fail "check_urdf: $(cat check.txt)"
  "$bin" axis "$src/data/axis_steps.csv" --linear -q -o linear.yaml &&
    "$bin" export linear.yaml --to urdf -o linear.urdf && check_urdf linear.urdf > check.txt 2>&1 && ok ||
    fail "check_urdf, linear axis: $(cat check.txt)"
else
  echo "check_urdf not installed (liburdfdom-tools): URDF not checked by its parser"
fi

# The C header from C and from C++: the values it holds are the file's.
ks=$(awk '/^  Ks:/ { gsub(/[{},]/, " "); print $3 }' axis.yaml)
printf '#include <stdio.h>\n#include "out.c-header"\nint main(void) { printf("%%.17g %%.3g\\n", SHOULDER_Ks, SHOULDER_Ks_STD); return 0; }\n' > use.c
cp out.c-header use.cc.h
printf '#include <cstdio>\n#include "out.c-header"\nstatic_assert(SHOULDER_Ka > 0.0, "constexpr");\nint main() { std::printf("%%.17g\\n", SHOULDER_Ks); }\n' > use.cc
if command -v cc > /dev/null && cc -std=c99 -Wall -Werror use.c -o use_c 2> cc.txt && [ "$(./use_c | cut -d' ' -f1)" = "$(printf '%.17g' "$ks")" ]; then
  ok
else
  fail "C header from C: $(cat cc.txt) $(./use_c 2>&1) vs Ks $ks"
fi
c++ -std=c++17 -Wall -Werror use.cc -o use_cc 2> cxx.txt && ./use_cc > /dev/null && ok || fail "C header from C++: $(cat cxx.txt)"

# Every target's values read back and compared with the parameter file (a
# gain written 5 % off fails here): the file's gains, then each target's.
gain() { awk -v k="$1" '$1 == k":" && /value:/ { gsub(/[{},]/, " "); print $3 }' axis.yaml; }
same_value() {  # same_value WHAT GOT WANT: equal to 1e-12 relative
  awk -v a="$2" -v b="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; s = b < 0 ? -b : b; exit !(a != "" && b != "" && d <= 1e-12 * s) }' ||
    { fail "$1: $2 read back, the parameter file has $3"; return 1; }
}
ks=$(gain Ks); kv=$(gain Kv); ka=$(gain Ka); koff=$(gain offset)
for key in Ks Kv Ka offset; do
  got=$(sed -n "s/.*\"$key\":{\"value\":\([-0-9.e+]*\).*/\1/p" out.json)
  same_value "json $key" "$got" "$(gain "$key")" && ok
done
same_value "urdf damping" "$(sed -n 's/.*damping="\([^"]*\)".*/\1/p' out.urdf)" "$kv" && ok
same_value "urdf friction" "$(sed -n 's/.*friction="\([^"]*\)".*/\1/p' out.urdf)" "$ks" && ok
same_value "urdf izz" "$(sed -n 's/.*izz="\([^"]*\)".*/\1/p' out.urdf)" "$ka" && ok
printf '#include <stdio.h>\n#include "out.c-header"\nint main(void) { printf("%%.17g %%.17g %%.17g %%.17g\\n", SHOULDER_Ks, SHOULDER_Kv, SHOULDER_Ka, SHOULDER_offset); return 0; }\n' > all.c
if command -v cc > /dev/null && cc -std=c99 -Wall -Werror all.c -o all_c 2> cc.txt; then
  read -r c_ks c_kv c_ka c_off < <(./all_c)
  same_value "C Ks" "$c_ks" "$ks" && same_value "C Kv" "$c_kv" "$kv" && same_value "C Ka" "$c_ka" "$ka" &&
    same_value "C offset" "$c_off" "$koff" && ok
else
  fail "C header read back: $(cat cc.txt)"
fi

if command -v javac > /dev/null; then
  # Stubs that keep their constructor's arguments: the factory's order is read back too.
  mkdir -p argstubs/edu/wpi/first/math/controller
  printf 'package edu.wpi.first.math.controller;\npublic class SimpleMotorFeedforward { public final double[] args; public SimpleMotorFeedforward(double a, double b, double c) { args = new double[] {a, b, c}; } }\n' \
    > argstubs/edu/wpi/first/math/controller/SimpleMotorFeedforward.java
  cp out.wpilib-java ShoulderFeedforwardGains.java
  printf 'public class ReadBack { public static void main(String[] x) { System.out.println(ShoulderFeedforwardGains.kS + " " + ShoulderFeedforwardGains.kV + " " + ShoulderFeedforwardGains.kA + " " + ShoulderFeedforwardGains.kOffset); double[] a = ShoulderFeedforwardGains.create().args; System.out.println(a[0] + " " + a[1] + " " + a[2]); } }\n' > ReadBack.java
  if javac -d readback argstubs/edu/wpi/first/math/controller/*.java ShoulderFeedforwardGains.java ReadBack.java 2> javac.txt &&
    java -cp readback ReadBack > java.txt 2>> javac.txt; then
    read -r j_ks j_kv j_ka j_off < <(sed -n 1p java.txt)
    read -r c_ks c_kv c_ka < <(sed -n 2p java.txt)
    same_value "Java kS" "$j_ks" "$ks" && same_value "Java kV" "$j_kv" "$kv" && same_value "Java kA" "$j_ka" "$ka" &&
      same_value "Java kOffset" "$j_off" "$koff" && same_value "Java create() kS" "$c_ks" "$ks" &&
      same_value "Java create() kV" "$c_kv" "$kv" && same_value "Java create() kA" "$c_ka" "$ka" && ok
  else
    fail "Java read back: $(cat javac.txt)"
  fi
  mkdir -p stubs/edu/wpi/first/math/controller
  for class in SimpleMotorFeedforward:3 ArmFeedforward:4 ElevatorFeedforward:4; do
    name=${class%%:*}
    args=$(seq -s, -f 'double a%g' "${class##*:}")
    printf 'package edu.wpi.first.math.controller;\npublic class %s { public %s(%s) {} }\n' "$name" "$name" "$args" \
      > "stubs/edu/wpi/first/math/controller/$name.java"
  done
  cp out.wpilib-java ShoulderFeedforwardGains.java
  javac -d classes stubs/edu/wpi/first/math/controller/*.java ShoulderFeedforwardGains.java 2> javac.txt && ok ||
    fail "javac: $(cat javac.txt)"
  # With gravity: ArmFeedforward(ks, kg, kv, ka).
  printf 'axis:\n  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1\n  gravity_cos: 4\n  gravity_sin: -3\nfeedforward:\n  law: axis\n  effort_unit: "V"\n  position_unit: "Radians"\n  Ks: {value: 1, std: 0.1}\n  Kv: {value: 0.2, std: 0.01}\n  Ka: {value: 0.05, std: 0.001}\n  Kg: {value: 5, std: 0.1}\n  Kg_angle: {value: -0.6435, std: 0.01}\n' > arm.yaml
  # (a joint named "arm": its class must not clash with WPILib's ArmFeedforward)
  "$bin" export arm.yaml --to wpilib-java --joint arm -o ArmFeedforwardGains.java &&
    grep -q "new ArmFeedforward(kS, kG, kV, kA)" ArmFeedforwardGains.java &&
    javac -d classes stubs/edu/wpi/first/math/controller/*.java ArmFeedforwardGains.java 2> javac.txt && ok ||
    fail "arm: $(cat javac.txt ArmFeedforwardGains.java)"
  # A linear axis with a constant force: ElevatorFeedforward(ks, kg, kv, ka).
  printf 'axis:\n  inertia: 12\n  viscous: 40\n  coulomb: 15\n  offset: 90\n  linear: true\nfeedforward:\n  law: axis\n  effort_unit: "N"\n  position_unit: "m"\n  Ks: {value: 15, std: 0.5}\n  Kv: {value: 40, std: 1}\n  Ka: {value: 12, std: 0.2}\n  offset: {value: 90, std: 1}\n' > lift.yaml
  "$bin" export lift.yaml --to wpilib-java --joint lift -o LiftFeedforwardGains.java &&
    grep -q "new ElevatorFeedforward(kS, kGElevator, kV, kA)" LiftFeedforwardGains.java &&
    javac -d classes stubs/edu/wpi/first/math/controller/*.java LiftFeedforwardGains.java 2> javac.txt && ok ||
    fail "elevator: $(cat javac.txt LiftFeedforwardGains.java)"
else
  echo "javac not installed: the Java export not compiled"
fi

# The MJCF in MuJoCo (validate MODEL.xml) against driveid's simulation of
# the same fit (validate P.yaml --simulate, Coulomb friction that sticks) on
# the shipped steps log, which rests between steps: fit % within 2 points,
# rotary (hinge) and linear (slide). docs/export.md#validation-in-mujoco.
fit_percent() { sed -n 's/.*"fit_percent":\([-0-9.e+]*\).*/\1/p' "$1"; }
steps="$src/data/axis_steps.csv"
if [ "$have_mujoco" = ON ]; then
  "$bin" axis "$steps" --linear -q -o linear.yaml || fail "linear axis fit"
  for kind in axis linear; do
    "$bin" export "$kind.yaml" --to mjcf -o "$kind.xml" &&
      "$bin" validate "$kind.yaml" "$steps" --simulate --json > own.json 2> stderr.txt &&
      "$bin" validate "$kind.xml" "$steps" --json > mujoco.json 2>> stderr.txt || fail "$kind: $(cat stderr.txt)"
    own=$(fit_percent own.json)
    mujoco=$(fit_percent mujoco.json)
    awk -v a="$own" -v b="$mujoco" 'BEGIN { exit !(a > 99 && b > 97 && a - b < 2 && b - a < 2) }' && ok ||
      fail "$kind: fit % driveid $own, MuJoCo $mujoco (not within 2 points)"
  done
  grep -q 'type="slide"' linear.xml && ok || fail "linear axis: no slide joint"
  # MuJoCo's default friction time constant (0.02 s) creeps ten times more at rest: the fit drops.
  soft=""
  sed 's/solreffriction="[^"]*"//' axis.xml > soft.xml
  "$bin" validate soft.xml "$steps" --json > soft.json && soft=$(fit_percent soft.json) &&
    awk -v a="$soft" -v b="$mujoco" 'BEGIN { exit !(a < b - 1) }' && ok || fail "default solref: fit % $soft"
  EXPECT_OUTPUT=--trace expect 3 "axis.xml \(joint 'nosuch'\): no hinge or slide joint 'nosuch' \(the file's: 'axis'" \
    -- validate axis.xml "$steps" --joint nosuch
  printf '<mujoco><worldbody><body><joint name="axis"/></body>\n' > cut.xml
  EXPECT_OUTPUT=--trace expect 3 "cut.xml .*MuJoCo cannot load it" -- validate cut.xml "$steps"
  sed 's|<general name="axis_motor"|<general name="second" joint="axis"/><general name="axis_motor"|' axis.xml > two.xml
  EXPECT_OUTPUT=--trace expect 3 "joint 'axis' has 2 actuators" -- validate two.xml "$steps"
  awk -F, '/^#/ || $3 == "tau" { print; next } { printf "%s,%s,%s\n", $1, $2, $3 * 1e12 }' "$steps" > huge.csv
  EXPECT_OUTPUT=--trace expect 4 "unstable: MuJoCo warned" -- validate axis.xml huge.csv
  # The elastic joint's MJCF in MuJoCo against driveid's own joint simulator
  # (simulate joint: RK4, sticking Coulomb on both sides), open loop, no noise:
  # motor and link angles within 2 points of a perfect fit.
  "$bin" simulate joint --params "$src/data/joint_example_truth.yaml" --duration 10 --amplitude 0.1 --band 0.5,20 \
    -o jsim.csv 2> stderr.txt &&
    "$bin" export "$src/data/joint_example_truth.yaml" --to mjcf --joint elbow -o elbow.xml 2>> stderr.txt &&
    "$bin" validate elbow.xml jsim.csv --model joint --joint elbow --json > joint.json 2>> stderr.txt ||
    fail "joint in MuJoCo: $(cat stderr.txt)"
  worst=$(grep -o '"fit_percent":[-0-9.e+]*' joint.json | cut -d: -f2 | sort -g | head -1)
  [ "$(grep -o '"fit_percent"' joint.json | wc -l)" -eq 2 ] && awk -v w="$worst" 'BEGIN { exit !(w > 98) }' && ok ||
    fail "joint in MuJoCo: lowest fit % $worst: $(cat joint.json)"
  EXPECT_OUTPUT=--trace expect 2 "--model joint: an elastic joint is validated from its MJCF" \
    -- validate "$src/data/joint_example_truth.yaml" jsim.csv --model joint
  EXPECT_OUTPUT=--trace expect 3 "no hinge or slide joint 'axis_motor'" -- validate elbow.xml jsim.csv --model joint
  # MuJoCo reads only files in the model's folder (issue 36: includes and
  # textures reached /etc and /dev): absolute paths, "..", character
  # references, links out and nested includes are refused before it starts.
  mkdir -p model
  cp axis.xml model/axis.xml
  printf '<mujoco><include file="../../etc/passwd"/></mujoco>\n' > model/sub.xml
  ln -sf /etc/hostname model/link.png
  hostile() { sed "s|<worldbody>|$1<worldbody>|" axis.xml > "model/$2.xml"; }
  hostile '<include file="../../etc/passwd"/>' dotdot
  hostile '<asset><texture name="t" type="2d" file="/dev/urandom"/></asset>' absolute
  hostile '<include file="\&#46;\&#46;/x.xml"/>' entity
  hostile '<include file="sub.xml"/>' nested
  cp model/sub.xml model/sub.inc
  hostile '<include file="sub.inc"/>' nested_inc
  sed 's|<mujoco model="driveid_axis">|<!-- parts: sub.xml --><mujoco model="driveid_axis"><include file="sub.xml"/>|' axis.xml \
    > model/nested_comment.xml
  hostile '<asset><texture name="t" type="2d" file="link.png"/></asset>' link
  hostile '<compiler meshdir="/etc"/>' meshdir
  for case in dotdot:"a '..'" absolute:"an absolute path" entity:"a character reference or entity" nested:"a '..'" nested_inc:"a '..'" nested_comment:"a '..'" \
              link:"a link that leads outside the model's folder" meshdir:"an absolute path"; do
    EXPECT_OUTPUT=--trace expect 3 "${case#*:}; MuJoCo may read only files in the model's folder" -- \
      validate "model/${case%%:*}.xml" "$steps"
  done
  # One sample compares nothing a simulation predicted (issue 36: rmse 0, exit 0).
  grep -v '^#' "$steps" | head -2 > one_sample.csv
  EXPECT_OUTPUT=--trace expect 4 "one_sample.csv:.*: 1 sample to compare, at least 3 are needed" -- validate axis.xml one_sample.csv
  EXPECT_OUTPUT=--trace expect 4 "one_sample.csv:.*: 1 sample to compare, at least 3 are needed" -- \
    validate axis.yaml one_sample.csv --simulate
  EXPECT_OUTPUT=--trace expect 2 "--simulate: an MJCF is always simulated" -- validate axis.xml "$steps" --simulate
  EXPECT_OUTPUT=--trace expect 2 "--mujoco-step" -- validate axis.xml "$steps" --mujoco-step 0
else
  "$bin" export axis.yaml --to mjcf -o axis.xml
  EXPECT_OUTPUT=--trace expect 3 "this build has no MuJoCo" -- validate axis.xml "$steps"
fi

# WPILib C++ (not in Debian): compiled against stub headers with WPILib's
# constructor signatures and the units library's type structure (unit_t,
# compound_unit, inverse; a unit_t converts from another unit_t as the units
# library's compatible units do), three classes, SysId's rotations too; the
# values printed equal the feed-forward section's.
mkdir -p cppstubs/frc/controller cppstubs/units
cat > cppstubs/units/base.h << 'STUB'
#pragma once
namespace units {
template <class... U> struct compound_unit_tag {};
template <class... U> using compound_unit = compound_unit_tag<U...>;
template <class U> struct inverse_tag {};
template <class U> using inverse = inverse_tag<U>;
struct volts {}; struct seconds {}; struct radians {}; struct turns {}; struct degrees {};
struct meters {}; struct millimeters {}; struct feet {}; struct inches {};
using radians_per_second = compound_unit<radians, inverse<seconds>>;
using meters_per_second = compound_unit<meters, inverse<seconds>>;
template <class U> class unit_t {
 public:
  constexpr explicit unit_t(double v) : v_(v) {}
  template <class V> constexpr unit_t(const unit_t<V>& other) : v_(other.value()) {}
  constexpr double value() const { return v_; }
 private:
  double v_;
};
using volt_t = unit_t<volts>;
using radian_t = unit_t<radians>;
}  // namespace units
STUB
for h in angle length time voltage; do echo '#include "base.h"' > "cppstubs/units/$h.h"; done
cat > cppstubs/frc/controller/SimpleMotorFeedforward.h << 'STUB'
#pragma once
#include <units/base.h>
namespace frc {
template <class Distance> class SimpleMotorFeedforward {
 public:
  using Velocity = units::compound_unit<Distance, units::inverse<units::seconds>>;
  using Acceleration = units::compound_unit<Velocity, units::inverse<units::seconds>>;
  using kv_unit = units::compound_unit<units::volts, units::inverse<Velocity>>;
  using ka_unit = units::compound_unit<units::volts, units::inverse<Acceleration>>;
  constexpr SimpleMotorFeedforward(units::volt_t kS, units::unit_t<kv_unit> kV,
                                   units::unit_t<ka_unit> kA = units::unit_t<ka_unit>(0)) : kS(kS), kV(kV), kA(kA) {}
  units::volt_t kS; units::unit_t<kv_unit> kV; units::unit_t<ka_unit> kA;
};
}  // namespace frc
STUB
for class in ArmFeedforward:radians ElevatorFeedforward:meters; do
  name=${class%%:*}
  unit=${class##*:}
  cat > "cppstubs/frc/controller/$name.h" << STUB
#pragma once
#include <units/base.h>
namespace frc {
class $name {
 public:
  using Velocity = units::compound_unit<units::$unit, units::inverse<units::seconds>>;
  using Acceleration = units::compound_unit<Velocity, units::inverse<units::seconds>>;
  using kv_unit = units::compound_unit<units::volts, units::inverse<Velocity>>;
  using ka_unit = units::compound_unit<units::volts, units::inverse<Acceleration>>;
  constexpr $name(units::volt_t kS, units::volt_t kG, units::unit_t<kv_unit> kV,
                  units::unit_t<ka_unit> kA = units::unit_t<ka_unit>(0)) : kS(kS), kG(kG), kV(kV), kA(kA) {}
  units::volt_t kS, kG; units::unit_t<kv_unit> kV; units::unit_t<ka_unit> kA;
};
}  // namespace frc
STUB
done
printf 'axis:\n  inertia: 0.01\n  viscous: 0.12\n  coulomb: 0.3\nfeedforward:\n  law: axis\n  effort_unit: "V"\n  position_unit: "Rotations"\n  Ks_forward: {value: 0.31, std: 0.01}\n  Ks_backward: {value: 0.29, std: 0.01}\n  Kv: {value: 0.12, std: 0.002}\n  Ka: {value: 0.01, std: 0.001}\n' > flywheel.yaml
sed 's/effort_unit: "N"/effort_unit: "V"/' lift.yaml > lift_volts.yaml
for case in flywheel:CreateForward:0.31 arm:Create:1 lift_volts:Create:15; do
  name=${case%%:*}; rest=${case#*:}; factory=${rest%%:*}; ks=${rest#*:}
  if "$bin" export "$name.yaml" --to wpilib-cpp --joint "$name" -o "$name.h" 2> stderr.txt; then
    printf '#include <cstdio>\n#include "%s.h"\nint main() { auto f = %s_feedforward::%s(); std::printf("%%.17g\\n", f.kS.value()); }\n' \
      "$name" "$name" "$factory" > "${name}_use.cc"
    if c++ -std=c++20 -Wall -Werror -I cppstubs "${name}_use.cc" -o "${name}_use" 2> cxx.txt &&
        [ "$(./"${name}_use")" = "$ks" ]; then
      ok
    else
      fail "wpilib-cpp $name: $(cat cxx.txt) $(./"${name}_use" 2>&1)"
    fi
  else
    fail "wpilib-cpp $name: $(cat stderr.txt)"
  fi
done
grep -q "using Distance = units::turns" flywheel.h && grep -q "frc::SimpleMotorFeedforward<Distance>" flywheel.h && ok ||
  fail "flywheel: $(cat flywheel.h)"
grep -q "frc::ElevatorFeedforward" lift_volts.h && grep -q "kGElevator{90}" lift_volts.h && ok || fail "elevator C++"
expect 3 "wpilib-cpp: WPILib's feed-forward classes take volts, and this fit's effort is in 'N m'" -- export axis.yaml --to wpilib-cpp
sed 's/position_unit: "Rotations"/position_unit: "furlongs"/' flywheel.yaml > furlong.yaml
expect 3 "position unit 'furlongs'" -- export furlong.yaml --to wpilib-cpp

# Feedback gains (drivetrain-fit gains, docs/export.md#feedback): the
# PIDController constants and factory in C++ (stub with WPILib's constructor
# PIDController(double, double, double, units::second_t)), Java (stub
# PIDController(double, double, double, double)) and the C header, each read
# back equal to the feedback section.
"$bin" gains flywheel.yaml --loop position --preset wpilib -o flywheel_pid.yaml > /dev/null 2>&1 || fail "gains for export"
kp=$(sed -n 's/^  kp: {value: \([^,]*\),.*/\1/p' flywheel_pid.yaml); kd=$(sed -n 's/^  kd: {value: \([^,]*\),.*/\1/p' flywheel_pid.yaml)
cat > cppstubs/frc/controller/PIDController.h << 'STUB'
#pragma once
#include <units/base.h>
namespace units { using second_t = unit_t<seconds>; }
namespace frc {
class PIDController {
 public:
  PIDController(double kp, double ki, double kd, units::second_t period) : kp(kp), ki(ki), kd(kd), period(period) {}
  double kp, ki, kd; units::second_t period;
};
}  // namespace frc
STUB
sed -i 's|^struct volts {}; struct seconds {};|struct volts {}; struct seconds {};|' cppstubs/units/base.h
"$bin" export flywheel_pid.yaml --to wpilib-cpp --joint flywheel -o flywheel_pid.h &&
  printf '#include <cstdio>\n#include "flywheel_pid.h"\nint main() { auto p = flywheel_feedforward::MakePIDController(); std::printf("%%.17g %%.17g %%.17g\\n", p.kp, p.kd, p.period.value()); }\n' > pid_use.cc &&
  c++ -std=c++20 -Wall -Werror -I cppstubs pid_use.cc -o pid_use 2> cxx.txt && read -r c_kp c_kd c_period < <(./pid_use) &&
  same_value "C++ kP" "$c_kp" "$kp" && same_value "C++ kD" "$c_kd" "$kd" && [ "$c_period" = "0.02" ] && ok ||
  fail "wpilib-cpp feedback: $(cat cxx.txt)"
# A vendor's gains go into its slot: the note, the constants, no PIDController.
"$bin" gains flywheel.yaml --loop position --preset ctre-phoenix6 -o flywheel_ctre.yaml > /dev/null 2>&1 || fail "gains, phoenix6"
"$bin" export flywheel_ctre.yaml --to wpilib-cpp --joint flywheel -o flywheel_ctre.h && 
  grep -q "CTRE Phoenix 6: new Slot0Configs().withKP(kP).withKD(kD)" flywheel_ctre.h && ! grep -q "PIDController{" flywheel_ctre.h &&
  ! grep -q "#include <frc/controller/PIDController.h>" flywheel_ctre.h && ok || fail "vendor slot note: $(cat flywheel_ctre.h)"
# The provenance line is the command as typed: it can be pasted back.
grep -q "^// made by: drivetrain-fit export flywheel_ctre.yaml --to wpilib-cpp --joint flywheel -o flywheel_ctre.h$" flywheel_ctre.h &&
  ok || fail "provenance: $(grep 'made by' flywheel_ctre.h)"
"$bin" export flywheel_pid.yaml --to c-header --joint flywheel -o flywheel_pid_c.h &&
  printf '#include <stdio.h>\n#include "flywheel_pid_c.h"\nint main(void) { printf("%%.17g %%.17g\\n", FLYWHEEL_FEEDBACK_KP, FLYWHEEL_FEEDBACK_KD); return 0; }\n' > pid_c.c &&
  cc -std=c99 -Wall -Werror pid_c.c -o pid_c 2> cc.txt && read -r h_kp h_kd < <(./pid_c) &&
  same_value "C kP" "$h_kp" "$kp" && same_value "C kD" "$h_kd" "$kd" && ok || fail "c-header feedback: $(cat cc.txt)"
if command -v javac > /dev/null; then
  mkdir -p pidstubs/edu/wpi/first/math/controller
  printf 'package edu.wpi.first.math.controller;\npublic class SimpleMotorFeedforward { public SimpleMotorFeedforward(double a, double b, double c) {} }\n' \
    > pidstubs/edu/wpi/first/math/controller/SimpleMotorFeedforward.java
  printf 'package edu.wpi.first.math.controller;\npublic class PIDController { public final double kp, kd, period; public PIDController(double p, double i, double d, double t) { kp = p; kd = d; period = t; } }\n' \
    > pidstubs/edu/wpi/first/math/controller/PIDController.java
  "$bin" export flywheel_pid.yaml --to wpilib-java --joint flywheel -o FlywheelFeedforwardGains.java &&
    printf 'public class PidBack { public static void main(String[] x) { var p = FlywheelFeedforwardGains.pidController(); System.out.println(p.kp + " " + p.kd + " " + p.period); } }\n' > PidBack.java &&
    javac -d pidclasses pidstubs/edu/wpi/first/math/controller/*.java FlywheelFeedforwardGains.java PidBack.java 2> javac.txt &&
    read -r j_kp j_kd j_period < <(java -cp pidclasses PidBack) &&
    same_value "Java kP" "$j_kp" "$kp" && same_value "Java kD" "$j_kd" "$kd" && ok || fail "wpilib-java feedback: $(cat javac.txt)"
fi

# The JSON export carries the feedback section too (issue 55: it was dropped).
"$bin" export flywheel_pid.yaml --to json --joint flywheel -o flywheel_pid.json &&
  json_kp=$(python3 -c 'import json,sys; f=json.load(open(sys.argv[1]))["feedback"]; print(f["loop"], f["values"]["kp"]["value"], f["values"]["kd"]["value"])' flywheel_pid.json) &&
  read -r j_loop j_kp j_kd <<< "$json_kp" && [ "$j_loop" = position ] && same_value "JSON kP" "$j_kp" "$kp" &&
  same_value "JSON kD" "$j_kd" "$kd" && ok || fail "json feedback: $(head -c 600 flywheel_pid.json)"
# A speed loop (PI with a notch) is written, not dropped: kP, kI, the period
# and C(z) as arrays in C++ and Java, C(s) and C(z) in JSON, each read back.
"$bin" gains "$src/data/joint_example_truth.yaml" --loop speed -o speed_gains.yaml > /dev/null 2>&1 || fail "gains --loop speed"
{ cat flywheel.yaml; awk '/^[a-z]/ { inside = /^feedback:/ } inside' speed_gains.yaml; } > flywheel_speed.yaml
cz0=$(sed -n 's/^  numerator_z: \[\([^,]*\),.*/\1/p' flywheel_speed.yaml)
ki=$(sed -n 's/^  ki: {value: \([^,]*\),.*/\1/p' flywheel_speed.yaml)
"$bin" export flywheel_speed.yaml --to wpilib-cpp --joint flywheel -o flywheel_speed.h &&
  printf '#include <cstdio>\n#include "flywheel_speed.h"\nint main() { using namespace flywheel_feedforward; std::printf("%%.17g %%.17g %%zu\\n", kI, kCzNumerator[0], kCzDenominator.size()); }\n' > speed_use.cc &&
  c++ -std=c++20 -Wall -Werror -I cppstubs speed_use.cc -o speed_use 2> cxx.txt && read -r s_ki s_cz0 s_den < <(./speed_use) &&
  same_value "C++ kI" "$s_ki" "$ki" && same_value "C++ C(z)" "$s_cz0" "$cz0" && [ "$s_den" = 4 ] &&
  grep -q "No PIDController holds the notch" flywheel_speed.h && ok || fail "wpilib-cpp speed loop: $(cat cxx.txt)"
"$bin" export flywheel_speed.yaml --to json --joint flywheel -o flywheel_speed.json &&
  python3 -c 'import json,sys; f=json.load(open(sys.argv[1]))["feedback"]; assert f["loop"] == "speed"; assert len(f["c_z"]["numerator"]) == 4; assert len(f["c_s"]["denominator"]) == 4' flywheel_speed.json &&
  ok || fail "json speed loop: $(head -c 600 flywheel_speed.json)"
if command -v javac > /dev/null; then
  "$bin" export flywheel_speed.yaml --to wpilib-java --joint flywheel -o FlywheelFeedforwardGains.java &&
    printf 'public class SpeedBack { public static void main(String[] x) { System.out.println(FlywheelFeedforwardGains.kI + " " + FlywheelFeedforwardGains.kCzNumerator[0]); } }\n' > SpeedBack.java &&
    javac -d speedclasses pidstubs/edu/wpi/first/math/controller/*.java FlywheelFeedforwardGains.java SpeedBack.java 2> javac.txt &&
    read -r js_ki js_cz0 < <(java -cp speedclasses SpeedBack) &&
    same_value "Java kI" "$js_ki" "$ki" && same_value "Java C(z)" "$js_cz0" "$cz0" && ok || fail "wpilib-java speed loop: $(cat javac.txt)"
fi
# A speed loop without its C(z) is refused by name, not exported without the notch.
grep -v "numerator_z\|denominator_z" flywheel_speed.yaml > speed_no_cz.yaml
expect 3 "feedback.numerator_z, denominator_z: missing from the speed loop's section" -- export speed_no_cz.yaml --to json

# The elastic joint (docs/export.md#elastic-joint): MJCF (loaded and checked
# in tests/export/mjcf_mujoco_test.cc), URDF through check_urdf, the C header
# compiled; no feed-forward targets; missing values named together.
truth="$src/data/joint_example_truth.yaml"
"$bin" export "$truth" --to mjcf --joint elbow -o joint.xml && grep -q '<fixed name="elbow_spring" stiffness="20"' joint.xml &&
  grep -q 'joint="elbow_motor" gear="50"' joint.xml && ok || fail "joint mjcf: $(head -c 600 joint.xml)"
"$bin" export "$truth" --to urdf --joint elbow -o joint.urdf && grep -q "no joint elasticity" joint.urdf && ok ||
  fail "joint urdf"
if command -v check_urdf > /dev/null; then
  check_urdf joint.urdf > check.txt 2>&1 && ok || fail "check_urdf, joint: $(cat check.txt)"
fi
"$bin" export "$truth" --to c-header --joint elbow -o joint.h &&
  printf '#include <stdio.h>\n#include "joint.h"\nint main(void) { printf("%%g %%g\\n", ELBOW_stiffness, ELBOW_gear_ratio); return 0; }\n' \
    > joint_use.c &&
  cc -std=c99 -Wall -Werror joint_use.c -o joint_use && [ "$(./joint_use)" = "20 50" ] && ok || fail "joint C header"
expect 3 "elastic joint has no feed-forward section" -- export "$truth" --to json
printf 'joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n' > joint_partial.yaml
expect 3 "joint.link_inertia, joint.stiffness: a simulator model" -- export joint_partial.yaml --to mjcf

# Refusals: a name that is no identifier (exit 2), a file without an axis (exit 3).
EXPECT_OUTPUT=-o expect 2 "--joint: joint name 'a-b'" -- export axis.yaml --to mjcf --joint a-b
expect 2 "--to" -- export axis.yaml --to sdf
expect 3 "no 'axis' or 'joint' section" -- export "$src/data/paper000.yaml" --to mjcf
# The C-drive's law (31) has no simulator or WPILib form (cdrive-fit export writes C and JSON).
{ grep -v '^#' "$src/data/cdrive_start.yaml"; printf 'feedforward:\n  law: cdrive\n  effort_unit: "N m"\n  position_unit: "rad"\n  beta: {value: 0.007, std: 0.0001}\n  gamma_half: {value: 0.001, std: 0.0001}\n  delta: {value: 0.3, std: 0.001}\n  eta: {value: 0.06, std: 0.001}\n  dead_zone: {value: 0.5, std: 0}\n  rate_limit: {value: 50, std: 0}\n'; } > comp.yaml
for target in mjcf urdf wpilib-java wpilib-cpp; do
  expect 3 "the C-drive's compensation law \(31\) couples the two motors" -- export comp.yaml --to "$target"
done
"$bin" export comp.yaml --to c-header | grep -q "DRIVEID_CONSTANT AXIS_gamma_half = 0.001;" && ok || fail "C-drive c-header"
# A unit with "*" beside a "/" cannot open a comment inside the C header's
# comment (issue 55: "/* V/*rad */", an error under gcc -Wall -Werror).
sed 's/position_unit: "Rotations"/position_unit: "*rad"/' flywheel_pid.yaml > star_unit.yaml
"$bin" export star_unit.yaml --to c-header --joint star -o star.h && printf '#include "star.h"\nint main(void) { return STAR_FEEDBACK_KP > 0 ? 0 : 1; }\n' > star.c &&
  cc -std=c99 -Wall -Wextra -Werror star.c -o star 2> cc.txt && ./star && ok || fail "'*rad' unit in the C header: $(cat cc.txt)"

# A negative std is refused by every command that reads the file (issue 55).
sed 's/Kv: {value: 0.12, std: 0.002}/Kv: {value: 0.12, std: -0.002}/' flywheel.yaml > negative_std.yaml
expect 3 "feedforward.Kv.std = -0.002: a standard error is >= 0" -- export negative_std.yaml --to json
for command in "report negative_std.yaml" "compare negative_std.yaml flywheel.yaml"; do
  # shellcheck disable=SC2086
  "$bin" $command > /dev/null 2> err.txt
  code=$?
  [ $code -eq 3 ] && grep -q "a standard error is >= 0" err.txt && ok || fail "$command: exit $code, $(cat err.txt)"
done
printf 'axis:\n  inertia: 0\n' > zero.yaml
expect 3 "axis.inertia = 0" -- export zero.yaml --to urdf
expect 3 "no axis 'feedforward' section" -- export zero.yaml --to json
finish
