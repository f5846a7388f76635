// The SDK's CosimHost::may_refuse (ABI 1.7, docs/decisions/0017-never-refuses.md) on hosts of two
// ABI minors: a 1.7 host's answer passes through; a host whose table ends before the field (1.6
// and older) is taken to allow refusals, so that a coupler keeps its checkpoints there.
#include <gtest/gtest.h>

#include <cstddef>
#include <rumble/plugin.hpp>

namespace {

int32_t only_the_soil_refuses(void* /*ctx*/, uint32_t participant) {
  return participant == rumble::CosimHost::kSoil ? 1 : 0;
}

TEST(CosimHostSdk, MayRefuseAsksAHostThatKnows) {
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.may_refuse = &only_the_soil_refuses;
  const rumble::CosimHost host(&table);
  EXPECT_FALSE(host.may_refuse(rumble::CosimHost::kTrack));
  EXPECT_TRUE(host.may_refuse(rumble::CosimHost::kSoil));
}

TEST(CosimHostSdk, MayRefuseOnAHostOlderThanItIsAlwaysTrue) {
  rumble_cosim_host table{};
  table.struct_size = offsetof(rumble_cosim_host, may_refuse);  // a 1.6 host's table
  table.may_refuse = &only_the_soil_refuses;                    // (beyond its end: never read)
  const rumble::CosimHost host(&table);
  EXPECT_TRUE(host.may_refuse(rumble::CosimHost::kTrack));
  rumble_cosim_host without{};
  without.struct_size = sizeof without;  // the field there, but null
  EXPECT_TRUE(rumble::CosimHost(&without).may_refuse(rumble::CosimHost::kTrack));
}

}  // namespace
