// rumble/host_resources.hpp against what the system says by other ways: `df`'s arithmetic
// (statvfs) for the disk, /proc/meminfo read by hand for the memory, and the size checks that
// rely on them (scenario/run_size.hpp check_machine_room).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/statvfs.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <rumble/host_resources.hpp>
#include <string>

#include "scenario/run_size.hpp"

namespace rumble {
namespace {

using ::testing::HasSubstr;

double meminfo_kib(const std::string& key) {
  std::ifstream in("/proc/meminfo");
  std::string name;
  double value = 0.0;
  std::string unit;
  while (in >> name >> value >> unit)
    if (name == key + ":") return value;
  return -1.0;
}

TEST(HostResources, AvailableMemoryIsMemAvailableAtMostAndPositive) {
  const double total = meminfo_kib("MemTotal") * 1024.0;
  ASSERT_GT(total, 0.0) << "no /proc/meminfo: not Linux";
  const double available = available_memory_bytes();
  EXPECT_GT(available, 0.0);
  EXPECT_LE(available, total);
  // MemAvailable moves as other processes run: the two readings agree to a few per cent of it.
  EXPECT_LE(available, meminfo_kib("MemAvailable") * 1024.0 * 1.05 + (64 << 20));
}

TEST(HostResources, FreeDiskOfAMissingPathIsItsNearestExistingParents) {
  const std::filesystem::path here = std::filesystem::current_path();
  struct statvfs fs {};
  ASSERT_EQ(::statvfs(here.c_str(), &fs), 0);
  const double expected = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
  const double measured = free_disk_bytes((here / "not" / "made" / "yet").string());
  // Other processes write meanwhile: within 1 GiB or 1 %.
  EXPECT_NEAR(measured, expected, std::max(double(1u << 30), 0.01 * expected));
  EXPECT_NEAR(free_disk_bytes("relative/not/made"), expected,
              std::max(double(1u << 30), 0.01 * expected));
  EXPECT_TRUE(std::isfinite(free_disk_bytes("/")));
}

/// The keys the size estimate reads, as a validated scenario has them (defaults filled).
nlohmann::json sized_scenario(double sleepers, double t_end, double macro_step) {
  return {{"time", {{"end", t_end}, {"macro_step", macro_step}}},
          {"track", {{"sleepers", {{"count", sleepers}}}}},
          {"vehicles", nlohmann::json::array({nlohmann::json::object()})},
          {"outputs", {{"every", 1}, {"receiver_interval", 0}}},
          {"coupling", {{"type", "gauss_seidel"}}}};
}

TEST(HostResources, ARunPastTheMachinesRoomIsRefusedAtTheValueToChange) {
  using scenario::check_machine_room;
  // 2000 sleepers: 56 x 2000^2 B = 214 MiB of statics; 0.1 s at 1 ms: a few hundred kB written.
  const nlohmann::json s = sized_scenario(2000, 0.1, 1e-3);
  EXPECT_TRUE(check_machine_room(s, {1e12, 1e12, "results"}).empty());
  const auto memory = check_machine_room(s, {100e6, 1e12, "results"});
  ASSERT_EQ(memory.size(), 1u);
  EXPECT_EQ(memory[0].pointer, "/track/sleepers/count");
  EXPECT_THAT(memory[0].message,
              HasSubstr("the run needs about 214 MiB of memory (214 MiB for the static state of "
                        "2000 sleepers"));
  EXPECT_THAT(memory[0].message, HasSubstr("more than the 95 MiB this machine has available now"));
  EXPECT_THAT(memory[0].hint, HasSubstr("use at most 1336 sleepers"));  // sqrt(1e8 / 56)
  const auto disk = check_machine_room(s, {1e12, 1e3, "results"});
  ASSERT_EQ(disk.size(), 1u);
  EXPECT_EQ(disk[0].pointer, "/outputs/every");
  EXPECT_THAT(disk[0].message, HasSubstr("more than the 1000 bytes free under results now"));
}

}  // namespace
}  // namespace rumble
