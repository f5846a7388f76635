// Every refusal of a bad mbs definition, with its exact text: where (JSON pointer relative to the
// params or the definition file), what, the value, and the fix.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "vehicle_harness.hpp"

namespace rumble::test {
namespace {

// A valid 3-body vehicle; each test breaks one thing in it.
std::string vehicle(const std::string& bodies_tail = "", const std::string& wheel_body = "ws",
                    const std::string& bogie_parent = "reference",
                    const std::string& bogie_mass = "1300") {
  return R"({"bodies": [
      {"name": "car_body", "mass": 15000, "transforms": [{"type": "tz", "value": -1.8, "dof": "zc"}]},
      {"name": "bogie_front", "parent": ")" +
         bogie_parent + R"(", "mass": )" + bogie_mass + R"(,
       "transforms": [{"type": "tz", "value": -0.6, "dof": "zb"}]},
      {"name": "ws", "mass": 900, "transforms": [{"type": "tz", "value": -0.46, "dof": "zw"}]})" +
         bodies_tail + R"(],
    "wheels": [{"body": ")" +
         wheel_body + R"("}]})";
}

TEST(MbsBadInput, ValidBaseVehicleIsAccepted) {
  EXPECT_EQ(creation_error("mbs", vehicle()), "");
}

TEST(MbsBadInput, ZeroMass) {
  EXPECT_EQ(creation_error("mbs", vehicle("", "ws", "reference", "0")),
            "params/bodies/1/mass: must be > 0 kg, got 0; give the body's mass in kg (one side of "
            "the vehicle)");
}

TEST(MbsBadInput, NegativeMass) {
  EXPECT_EQ(creation_error("mbs", vehicle("", "ws", "reference", "-1300.5")),
            "params/bodies/1/mass: must be > 0 kg, got -1300.5; give the body's mass in kg (one "
            "side of the vehicle)");
}

TEST(MbsBadInput, UnknownParentSuggestsTheClosestName) {
  EXPECT_EQ(creation_error("mbs", vehicle("", "ws", "car_bdy")),
            "params/bodies/1/parent: no body is named \"car_bdy\" (did you mean \"car_body\"?); "
            "name one of the bodies (car_body, bogie_front, ws) or \"reference\" for the vehicle "
            "frame");
}

TEST(MbsBadInput, ParentCycle) {
  const std::string tail =
      R"(, {"name": "a", "parent": "b", "mass": 1, "transforms": [{"type": "tz", "dof": "za"}]},
         {"name": "b", "parent": "a", "mass": 1})";
  EXPECT_EQ(creation_error("mbs", vehicle(tail)),
            "params/bodies/3/parent: the bodies' parents form a cycle: a -> b -> a; every chain "
            "of parents must end at \"reference\"; attach one of these bodies to \"reference\" or "
            "to a body outside the cycle");
}

TEST(MbsBadInput, BodyIsItsOwnParent) {
  const std::string tail = R"(, {"name": "a", "parent": "a", "mass": 1})";
  EXPECT_EQ(creation_error("mbs", vehicle(tail)),
            "params/bodies/3/parent: the bodies' parents form a cycle: a -> a; every chain of "
            "parents must end at \"reference\"; attach one of these bodies to \"reference\" or to "
            "a body outside the cycle");
}

TEST(MbsBadInput, DofNameUsedTwice) {
  const std::string tail =
      R"(, {"name": "ws2", "mass": 900, "transforms": [{"type": "tz", "dof": "zb"}]})";
  EXPECT_EQ(creation_error("mbs", vehicle(tail)),
            "params/bodies/3/transforms/0/dof: DOF \"zb\" already drives "
            "params/bodies/1/transforms/0; a DOF drives exactly one transformation; give this one "
            "another name");
}

TEST(MbsBadInput, WheelOnUnknownBody) {
  EXPECT_EQ(creation_error("mbs", vehicle("", "wheelset")),
            "params/wheels/0/body: no body is named \"wheelset\"; name one of the bodies "
            "(car_body, bogie_front, ws)");
}

TEST(MbsBadInput, WheelOnTheReferenceFrame) {
  EXPECT_EQ(creation_error("mbs", vehicle("", "reference")),
            "params/wheels/0/body: must be a body, not the reference frame, got \"reference\"; "
            "name one of the bodies");
}

TEST(MbsBadInput, WheelOnABodyNoDofMoves) {
  const std::string tail = R"(, {"name": "fixed", "mass": 10})";
  EXPECT_EQ(creation_error("mbs", vehicle(tail, "fixed")),
            "params/wheels/0/body: the wheel centre does not move vertically with any DOF, so the "
            "contact force has nothing to act on, got \"fixed\"; drive this body (or one of its "
            "parents) with a \"tz\" transformation that has a \"dof\"");
}

TEST(MbsBadInput, MisspeltKey) {
  const std::string params = R"({"bodies": [{"name": "w", "mass": 1, "transfroms": []}],
                                 "wheels": [{"body": "w"}]})";
  EXPECT_EQ(creation_error("mbs", params),
            "params/bodies/0/transfroms: unknown key (did you mean \"transforms\"?); allowed keys "
            "here: inertia, mass, name, parent, transforms");
}

TEST(MbsBadInput, MisspeltOptionalKey) {
  const std::string params =
      R"({"bodies": [{"name": "w", "mass": 1, "transforms": [{"type": "tz", "dfo": "z"}]}],
          "wheels": [{"body": "w"}]})";
  EXPECT_EQ(creation_error("mbs", params),
            "params/bodies/0/transforms/0/dfo: unknown key (did you mean \"dof\"?); allowed keys "
            "here: dof, type, value");
}

TEST(MbsBadInput, UnknownTransformation) {
  const std::string params =
      R"({"bodies": [{"name": "w", "mass": 1, "transforms": [{"type": "rz", "dof": "z"}]}],
          "wheels": [{"body": "w"}]})";
  EXPECT_EQ(creation_error("mbs", params),
            "params/bodies/0/transforms/0/type: unknown transformation (did you mean \"tz\"?), got "
            "\"rz\"; use \"tx\" or \"tz\" (translation along the current x or z axis, m) or \"ry\" "
            "(rotation about y, rad, positive lifts the front)");
}

TEST(MbsBadInput, DofWithoutInertia) {
  // A pitch DOF of a body with no pitch inertia whose centre of mass is on the axis: M singular.
  const std::string params = R"({"bodies": [{"name": "w", "mass": 1, "transforms": [
      {"type": "tz", "dof": "z"}, {"type": "ry", "dof": "pitch"}]}], "wheels": [{"body": "w"}]})";
  EXPECT_EQ(creation_error("mbs", params),
            "params/bodies/0/transforms/1/dof: the mass matrix is singular at q = 0: DOF \"pitch\" "
            "moves no mass or inertia that the DOFs before it do not already move; place a body "
            "with mass (for a rotation: pitch inertia, or a centre of mass off the axis) after "
            "this transformation, or remove the DOF");
}

TEST(MbsBadInput, ElementJoiningABodyToItself) {
  const std::string params = R"({"bodies": [{"name": "w", "mass": 1, "transforms": [
      {"type": "tz", "dof": "z"}]}], "elements": [{"body_a": "w", "body_b": "w", "k": 1}],
      "wheels": [{"body": "w"}]})";
  EXPECT_EQ(creation_error("mbs", params),
            "params/elements/0/body_b: an element must join two different bodies, got \"w\"; name "
            "another body (or \"reference\") for body_a or body_b");
}

TEST(MbsBadInput, FileAndInlineDefinitionTogether) {
  EXPECT_EQ(creation_error("mbs", R"({"file": "half_train.json", "gravity": 9.81})"),
            "params/gravity: not allowed together with \"file\"; put the whole definition in the "
            "file, or give it inline without \"file\"");
}

TEST(MbsBadInput, MissingFile) {
  const std::string dir = vehicles_dir();
  EXPECT_EQ(creation_error("mbs", R"({"file": "no_such_train.json"})"),
            "params/file: no such file \"" + dir +
                "/no_such_train.json\", got \"no_such_train.json\"; give the path of a vehicle "
                "definition relative to the scenario file's directory (\"" +
                dir + "\")");
}

// A scenario named as "x.json" has the directory "" (the current one): the message says ".".
TEST(MbsBadInput, MissingFileNextToAScenarioInTheCurrentDirectory) {
  EXPECT_EQ(creation_error("mbs", R"({"file": "nothere.json"})", ""),
            "params/file: no such file \"./nothere.json\", got \"nothere.json\"; give the path "
            "of a vehicle definition relative to the scenario file's directory (\".\")");
}

// Issue #8: /dev/zero was read until memory ran out (4 GB), a FIFO blocked, a text file gave the
// parser's raw text. Only regular files of at most 1 MiB are read.
TEST(MbsBadInput, DeviceDirectoryAndFifoAreNotDefinitions) {
  EXPECT_EQ(creation_error("mbs", R"({"file": "/dev/zero"})"),
            "params/file: \"/dev/zero\" is not a regular file (a directory, device or pipe), got "
            "\"/dev/zero\"; name a vehicle definition file (JSON)");
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "rumble_mbs_bad_file_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "sub");
  EXPECT_EQ(creation_error("mbs", R"({"file": "sub"})", dir.string()),
            "params/file: \"" + (dir / "sub").string() +
                "\" is not a regular file (a directory, device or pipe), got \"sub\"; name a "
                "vehicle definition file (JSON)");
  ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0600), 0);
  EXPECT_EQ(creation_error("mbs", R"({"file": "fifo"})", dir.string()),
            "params/file: \"" + (dir / "fifo").string() +
                "\" is not a regular file (a directory, device or pipe), got \"fifo\"; name a "
                "vehicle definition file (JSON)");
  std::filesystem::remove_all(dir);
}

TEST(MbsBadInput, LargeFileIsRefusedUnread) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "rumble_mbs_large_file_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "big.json") << "{}";
  std::filesystem::resize_file(dir / "big.json", 3u << 20);  // sparse: costs no disk
  EXPECT_EQ(creation_error("mbs", R"({"file": "big.json"})", dir.string()),
            "params/file: \"" + (dir / "big.json").string() +
                "\" is too large (3145728 bytes; a vehicle definition is at most 1048576 bytes), "
                "got \"big.json\"; is this the right file?");
  std::filesystem::remove_all(dir);
}

TEST(MbsBadInput, TextThatIsNotJsonSaysWhereWithoutTheParsersTag) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "rumble_mbs_not_json_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "passwd") << "root:x:0:0:root:/root:/bin/bash\n";
  EXPECT_EQ(creation_error("mbs", R"({"file": "passwd"})", dir.string()),
            "passwd#: not valid JSON: parse error at line 1, column 1: syntax error while parsing "
            "value - invalid literal; last read: 'r'; a vehicle definition is one JSON object "
            "(docs/vehicles.md); is this the right file?");
  std::filesystem::remove_all(dir);
}

// A key written twice in a definition file: the first value would be dropped without a word.
TEST(MbsBadInput, DuplicateKeyInAFileIsPointedAt) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "rumble_mbs_duplicate_key_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "dup.json")
      << R"({"bodies": [{"name": "w", "mass": 900, "transforms": [{"type": "tz", "dof": "z"}]},
                        {"name": "v", "mass": 1, "mass": 2}],
             "wheels": [{"body": "w"}]})";
  EXPECT_EQ(creation_error("mbs", R"({"file": "dup.json"})", dir.string()),
            "dup.json#/bodies/1/mass: duplicate key; JSON keeps only the last value and would "
            "drop the other without a word; keep one of the two");
  std::filesystem::remove_all(dir);
}

TEST(MbsBadInput, ErrorsInAFileArePointedInThatFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "rumble_mbs_bad_input_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bad.json") << R"({"bodies": [{"name": "w", "mass": -2}], "wheels": []})";
  EXPECT_EQ(creation_error("mbs", R"({"file": "bad.json"})", dir.string()),
            "bad.json#/bodies/0/mass: must be > 0 kg, got -2; give the body's mass in kg (one "
            "side of the vehicle)");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rumble::test
