#include "plugin/soil_server.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "parallel/mirror_transport.hpp"
#include "plugin/instance.hpp"
#include "plugin/mirror_message.hpp"
#include "plugin/registry.hpp"

namespace rumble {
namespace {

using mirror::Call;
using mirror::Reader;

void host_context(SoilInstance& soil, Reader& r) {
  const std::string results_dir = r.get_text();
  const auto threads = r.get<std::uint32_t>();
  soil.set_results_dir(results_dir);
  soil.grant_threads(threads);
}

void checkpoints(SoilInstance& soil, Call call, Reader& r) {
  switch (call) {
    case Call::kCanCheckpoint:
      soil.can_checkpoint();
      return;
    case Call::kCheckpointSave:
      soil.checkpoint_save(r.get<std::uint32_t>());
      return;
    case Call::kCheckpointRestore:
      soil.checkpoint_restore(r.get<std::uint32_t>());
      return;
    default:
      soil.checkpoint_free(r.get<std::uint32_t>());
  }
}

void advance(SoilInstance& soil, Reader& r) {
  const auto t = r.get<double>();
  const auto H = r.get<double>();
  const auto order = r.get<std::uint32_t>();
  const std::vector<double> coeff = r.get_array<double>();
  const rumble_waveform force{order, coeff.size() / (order + 1), coeff.data()};
  soil.advance(t, H, force);
}

void set_probes(SoilInstance& soil, Reader& r) {
  const auto interval = r.get<double>();
  const auto n = r.get<std::uint64_t>();
  std::vector<std::string> names(n);
  std::vector<rumble_probe> probes(n);
  for (std::size_t p = 0; p < n; ++p) {
    names[p] = r.get_text();
    probes[p] = {names[p].c_str(), r.get<double>(), r.get<double>(), r.get<double>()};
  }
  soil.set_probes(probes, interval);
}

/// The outputs of these calls are rank 0's: a server makes them for their collective part.
void outputs(SoilInstance& soil, Call call, Reader& r) {
  std::vector<double> a, b;
  switch (call) {
    case Call::kMotion: {
      const auto n = static_cast<std::size_t>(r.get<std::uint64_t>());
      a.resize(n);
      b.resize(n);
      soil.motion(a.data(), b.data(), n);
      return;
    }
    case Call::kReceiverVelocity: {
      a.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
      soil.receiver_velocity(a.data(), a.size());
      return;
    }
    case Call::kFrequencyResponse: {
      const auto f = r.get<double>();
      std::vector<std::complex<double>> receptance;
      soil.frequency_response(f, static_cast<std::size_t>(r.get<std::uint64_t>()), receptance);
      return;
    }
    case Call::kTakeProbeSamples:
      soil.take_probe_samples(a, b);
      return;
    case Call::kProbeResolution:
      soil.probe_resolution();
      return;
    case Call::kLinearMatrix: {
      Eigen::SparseMatrix<double> m;
      soil.linear_matrix(r.get<rumble_matrix>(), m);
      return;
    }
    case Call::kSize:
      soil.size();
      return;
    default: {
      double c_s = 0.0, c_r = 0.0;
      soil.wave_speeds(c_s, c_r);
    }
  }
}

}  // namespace

void SoilServer::create(Reader& r, std::uint64_t id) {
  const std::string library = r.get_text();
  const std::string type_name = r.get_text();
  const std::string label = r.get_text();
  const std::string params = r.get_text();
  const std::string scenario_dir = r.get_text();
  registry_.load_library(library, "rank 0's");  // once: a second load finds it loaded
  const ComponentType* type = registry_.find(RUMBLE_KIND_SOIL, type_name);
  if (type == nullptr) throw RunError("no soil type '" + type_name + "' in " + library);
  soils_[id] =
      std::make_unique<SoilInstance>(*type, label, nlohmann::json::parse(params), scenario_dir);
}

SoilInstance& SoilServer::at(std::uint64_t id) {
  const auto it = soils_.find(id);
  if (it == soils_.end()) throw RunError("no copy of instance " + std::to_string(id));
  return *it->second;
}

/// Makes one call on this rank's copy.
void SoilServer::make(Call call, std::uint64_t id, Reader& r) {
  if (call == Call::kCreate) return create(r, id);
  if (call == Call::kDestroy) {
    soils_.erase(id);
    return;
  }
  SoilInstance& soil = at(id);
  switch (call) {
    case Call::kHostContext:
      return host_context(soil, r);
    case Call::kFinalize:
      return soil.finalize();
    case Call::kCanCheckpoint:
    case Call::kCheckpointSave:
    case Call::kCheckpointRestore:
    case Call::kCheckpointFree:
      return checkpoints(soil, call, r);
    case Call::kAcceptLayout:
      return soil.accept_layout(r.get_array<rumble_footprint>());
    case Call::kInitialize: {
      const auto t0 = r.get<double>();
      std::vector<double> u;
      return soil.initialize(t0, r.get_array<double>(), u);
    }
    case Call::kAdvance:
      return advance(soil, r);
    case Call::kSetReceivers:
      soil.set_receivers(r.get_array<rumble_receiver>());
      return;
    case Call::kSetProbes:
      return set_probes(soil, r);
    case Call::kWriteFields: {
      const auto t = r.get<double>();
      soil.write_fields(t, r.get_text());
      return;
    }
    case Call::kStaticsDone:
      return soil.statics_done();
    default:
      return outputs(soil, call, r);
  }
}

void SoilServer::serve(Reader& message) {
  std::string error;
  try {
    const auto call = message.get<Call>();
    make(call, message.get<std::uint64_t>(), message);
  } catch (const std::exception& e) {
    error = e.what();
  }
  parallel::first_failure(error);
}

}  // namespace rumble
