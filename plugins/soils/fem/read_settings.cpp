// read_settings: the FEM soil's params, validated against the schema (fem_schema.cpp) and filled
// with its defaults by the host, read once into FemSettings with the SDK's rumble::Params against
// the same schema (so a caller of the C API that fills no default reads the schema's own, and no
// default is written here). Each object of the params has its reader; what the schema cannot say
// (relations between keys, the matched layer's size, the Maxwell fit) is checked here, with the
// key, the rule, the value and the fix. Ranges and defaults are the schema's alone: none is
// repeated here.
#include <iomanip>
#include <rumble/params.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fem_schema.hpp"
#include "fem_settings.hpp"
#include "results_file.hpp"
#include "soil_params.hpp"

namespace rumble::fem {

namespace {

[[noreturn]] void refuse(const std::string& key, const std::string& rule, double value) {
  std::ostringstream m;
  m << "fem: params/" << key << ": " << rule << ", got " << value;
  throw std::invalid_argument(m.str());
}

// A lower bound on the DOFs of a perfectly matched layer [-]: its shell around the box is at
// least 12 radius^2 x thickness (a bottom of 2 radius x 2 radius, four sides of 2 radius x
// radius), meshed at most thickness / elements, with 0.8 / h^3 nodes per unit volume and 3 DOFs
// per node as the mesh's own estimate (docs/fem-soil.md section 2). That estimate samples the
// domain on a grid that a layer thinner than about radius / 30 falls between; this bound refuses
// such a layer before gmsh spends hours (or all the memory) on it (docs/scenario.md, "Limits").
double pml_dofs_at_least(double radius, double thickness, double elements) {
  const double h = thickness / elements;
  return 3.0 * 0.8 * 12.0 * radius * radius * thickness / (h * h * h);
}

// The Maxwell fit's largest miss of the ratio over its band accepted [-]: three mechanisms on
// 5-100 Hz miss by 2.8 %; beyond 10 % the band is too wide or too narrow for the mechanisms.
constexpr double kMaxwellBandError = 0.1;

// The layers' names (optional, "" for none): unique, and none of the names a mesh file's volumes
// have already.
std::vector<std::string> read_layer_names(const nlohmann::json& params) {
  std::vector<std::string> names;
  if (!params.contains("layers")) return names;
  for (std::size_t k = 0; k < params.at("layers").size(); ++k) {
    const nlohmann::json& layer = params.at("layers").at(k);
    std::string name = layer.contains("name") ? layer.at("name").get<std::string>() : "";
    const std::string where = "layers/" + std::to_string(k) + "/name";
    const bool numbered = name.rfind("layer_", 0) == 0 && name.size() > 6 &&
                          name.find_first_not_of("0123456789", 6) == std::string::npos;
    if (name == "half_space" || numbered)
      throw std::invalid_argument("fem: params/" + where + ": \"" + name +
                                  "\" is a name the mesh file's volumes have already "
                                  "(half_space, layer_<k>); choose another");
    for (std::size_t i = 0; i < k && !name.empty(); ++i)
      if (names[i] == name)
        throw std::invalid_argument("fem: params/" + where + ": \"" + name +
                                    "\" names params/layers/" + std::to_string(i) +
                                    " already; give each layer its own name");
    names.push_back(std::move(name));
  }
  return names;
}

// What the schema cannot say of the mesh: mesh.export inside the results directory (also without
// the schema: issue 30), not with mesh.file, and h_near within h_max.
void check_mesh(const MeshRequest& m) {
  if (const std::string why = outside_results(m.export_file);
      !m.export_file.empty() && !why.empty())
    throw std::invalid_argument("fem: params/mesh/export: \"" + m.export_file + "\": " + why +
                                "; " + kExportRule);
  if (!m.file.empty() && !m.export_file.empty())
    throw std::invalid_argument("fem: params/mesh/export: \"" + m.export_file +
                                "\" would write the soil's own mesh, but mesh.file \"" + m.file +
                                "\" is the mesh here; drop one of them");
  if (m.h_max > 0.0 && m.h_near > m.h_max)
    refuse("mesh/h_near", "must not exceed mesh/h_max (" + std::to_string(m.h_max) + " m)",
           m.h_near);
}

MeshRequest read_mesh(const rumble::Params& mesh) {
  MeshRequest m;
  m.shape = mesh.get<std::string>("shape") == "box" ? MeshShape::kBox : MeshShape::kHemisphere;
  m.radius = mesh.get<double>("radius");
  m.f_max = mesh.get<double>("f_max");
  m.elements_per_wavelength = mesh.get<double>("elements_per_wavelength");
  m.near_distance = mesh.get<double>("near_distance");
  // Derived when not given (0): plan_mesh takes them from f_max and the slowest Rayleigh speed,
  // and from the radius.
  m.h_near = mesh.optional<double>("h_near").value_or(0.0);
  m.h_max = mesh.optional<double>("h_max").value_or(0.0);
  m.max_dofs = mesh.get<double>("max_dofs");
  m.fast_algorithm = mesh.get<std::string>("algorithm") == "hxt";
  m.quality_threshold = mesh.get<double>("quality_threshold");
  m.refine = mesh.get<int>("refine");
  m.file = mesh.optional<std::string>("file").value_or("");
  m.export_file = mesh.optional<std::string>("export").value_or("");
  check_mesh(m);
  return m;
}

// A generated layer must fit mesh.max_dofs: refused before gmsh meshes it.
void check_pml_size(const BoundaryRequest& b, const MeshRequest& m) {
  const double dofs = pml_dofs_at_least(m.radius, b.pml_thickness, b.pml_elements);
  if (dofs <= m.max_dofs) return;
  std::ostringstream rule;
  rule << std::setprecision(3) << "a layer of this thickness in elements of at most "
       << b.pml_thickness / b.pml_elements
       << " m (thickness / pml.elements) around a box of mesh.radius " << m.radius
       << " m needs at least " << dofs
       << " degrees of freedom, more than mesh.max_dofs = " << m.max_dofs
       << "; thicken the layer (about mesh.radius / 2), use fewer pml.elements, a smaller "
          "mesh.radius, or raise mesh.max_dofs (about 1.5 GB per million DOFs at a run's peak)";
  refuse("boundary/pml/thickness", rule.str(), b.pml_thickness);
}

// boundary.pml, which the schema refuses under another boundary.type and fills only under pml.
void read_pml(const rumble::Params& pml, const MeshRequest& m, BoundaryRequest& b) {
  // Derived when not given: mesh.radius / 2 (the schema's description says so).
  b.pml_thickness = pml.optional<double>("thickness").value_or(0.5 * m.radius);
  b.pml_reflection = pml.get<double>("reflection");
  b.pml_elements = pml.get<double>("elements");
  if (m.file.empty()) check_pml_size(b, m);
}

BoundaryRequest read_boundary(const rumble::Params& boundary, const MeshRequest& m) {
  BoundaryRequest b;
  const std::string kind = boundary.get<std::string>("type");
  b.kind = kind == "fixed"     ? BoundaryKind::kFixed
           : kind == "dashpot" ? BoundaryKind::kDashpot
           : kind == "pml"     ? BoundaryKind::kPml
                               : BoundaryKind::kViscousSpring;
  if (b.kind == BoundaryKind::kPml) read_pml(boundary.object("pml"), m, b);
  b.spring_model =
      boundary.get<std::string>("springs") == "liu" ? SpringModel::kLiu : SpringModel::kHalfSpace;
  b.far_field_follows = boundary.get<std::string>("far_field") == "follows";
  // Liu's normal springs alone read alpha_normal: the schema refuses it with the half-space
  // springs and fills it only with liu.
  if (b.spring_model == SpringModel::kLiu) b.alpha_normal = boundary.get<double>("alpha_normal");
  b.alpha_tangential = boundary.get<double>("alpha_tangential");
  return b;
}

// The mechanisms must carry the ratio over the band, with positive weights.
void check_maxwell_fit(const DampingRequest& damping) {
  const MaxwellDamping d = damping.maxwell_mechanisms();
  const double error = d.band_error(damping.ratio, damping.f_low, damping.f_high);
  if (d.dissipative() && error <= kMaxwellBandError) return;
  // Too few mechanisms for the band miss the ratio between them; too many for it (or too high a
  // ratio) need a negative weight.
  std::ostringstream message;
  message << std::setprecision(3) << "fem: params/damping: " << d.mechanisms()
          << " Maxwell mechanisms fitted to the ratio " << damping.ratio << " over "
          << damping.f_low << "-" << damping.f_high << " Hz ";
  if (d.dissipative())
    message << "miss it by " << 100.0 * error << " % (at most " << 100.0 * kMaxwellBandError
            << " %); use more mechanisms (about one per half decade of the band)";
  else
    message << "need a negative weight (one would feed energy in); use fewer mechanisms "
               "(about one per half decade of the band), a wider band or a lower ratio";
  message << ", got mechanisms " << damping.mechanisms;
  throw std::invalid_argument(message.str());
}

DampingRequest read_damping(const rumble::Params& damping) {
  DampingRequest d;
  d.ratio = damping.get<double>("ratio");
  d.f_low = damping.get<double>("f_low");
  d.f_high = damping.get<double>("f_high");
  if (d.ratio > 0.0 && !(d.f_high > d.f_low))
    refuse("damping/f_high", "must exceed damping/f_low (" + std::to_string(d.f_low) + " Hz)",
           d.f_high);
  d.maxwell = damping.get<std::string>("model") == "maxwell";
  // The schema refuses mechanisms under Rayleigh's model and fills it only under maxwell.
  if (d.maxwell) d.mechanisms = damping.get<int>("mechanisms");
  if (d.maxwell && d.ratio > 0.0) check_maxwell_fit(d);
  return d;
}

ReceptanceRequest read_receptance(const rumble::Params& receptance, const MeshRequest& m) {
  ReceptanceRequest r;
  r.impulse = receptance.get<std::string>("method") == "impulse";
  r.duration = receptance.get<double>("duration");
  // The impulse responses' pulse is 0.5 / mesh.f_max long (impulse_receptance.hpp); a record
  // shorter than a few pulses holds no decay.
  if (r.impulse && r.duration < 2.0 / m.f_max)
    refuse("receptance/duration",
           "must be at least 4 times the impulse's pulse 0.5 / mesh.f_max (" +
               std::to_string(2.0 / m.f_max) +
               " s), and long enough for the motion to die out "
               "(2 s by default)",
           r.duration);
  return r;
}

// The integrator's keys and courant (at the params' top level).
void read_integrator(const rumble::Params& params, FemSettings& s) {
  s.courant = params.get<double>("courant");
  const rumble::Params integrator = params.object("integrator");
  s.implicit = integrator.get<std::string>("scheme") == "implicit";
  // Derived when not given: 20 steps per period at mesh.f_max (the schema's description).
  s.implicit_step = integrator.optional<double>("max_step").value_or(1.0 / (20.0 * s.mesh.f_max));
  s.local_steps = integrator.get<int>("local_steps");
  if (s.implicit && s.local_steps > 1)
    refuse("integrator/local_steps",
           "local time stepping lifts the explicit step's limit and the implicit scheme has none; "
           "use integrator.scheme \"explicit\" or drop local_steps",
           s.local_steps);
  // The implicit scheme factors K in double; precision does not apply there, as courant does
  // not, and is not refused with it (its default is filled in under either scheme).
  s.single_precision_step = !s.implicit && integrator.get<std::string>("precision") == "single";
}

// What the matched layer needs of the other settings.
void check_pml_needs(const FemSettings& s) {
  if (s.boundary.kind != BoundaryKind::kPml) return;
  const auto pml_needs = [](const std::string& key, const std::string& what) {
    throw std::invalid_argument("fem: params/" + key + ": boundary.type \"pml\" needs " + what +
                                "; use boundary.type \"viscous_spring\" otherwise");
  };
  if (!s.mesh.file.empty())
    pml_needs("mesh/file", "a generated mesh (its layer is meshed around the box)");
  if (s.mesh.shape != MeshShape::kBox)
    pml_needs("mesh/shape", "mesh.shape \"box\" (the layer stretches the box's axes)");
  if (s.implicit)
    pml_needs("integrator/scheme",
              "the explicit integrator (its memory variables are stepped explicitly)");
}

// The geometric multigrid's coarse level is gmsh's mesh before mesh.refine refined it.
void check_geometric_needs(const FemSettings& s) {
  if (!s.geometric_statics) return;
  if (!s.mesh.file.empty())
    throw std::invalid_argument(
        "fem: params/statics/solver: \"geometric\" needs a generated mesh refined by "
        "mesh.refine (its coarse level is gmsh's mesh before the refinement), but mesh.file \"" +
        s.mesh.file + "\" is the mesh here; use statics.solver \"gamg\" or \"auto\"");
  if (s.mesh.refine < 1)
    throw std::invalid_argument(
        "fem: params/statics/solver: \"geometric\" needs mesh.refine 1 or more (its coarse "
        "level is gmsh's mesh before the refinement; docs/fem-soil.md section 7.1), got "
        "params/mesh/refine " +
        std::to_string(s.mesh.refine) +
        ": set mesh.refine to 1 (gmsh then meshes at twice the sizes), or use statics.solver "
        "\"gamg\" or \"auto\"");
}

}  // namespace

FemSettings read_settings(const std::string& params_json) {
  const soils::SoilParams soil(params_json, "fem");
  const rumble::Params params(params_json, settings_schema(), "fem");
  FemSettings s;
  s.half_space = soil.half_space();
  s.layers = soil.layers();
  s.layer_names = read_layer_names(params.json());
  s.mesh = read_mesh(params.object("mesh"));
  s.mesh_threads = params.object("mesh").get<unsigned>("threads");
  s.boundary = read_boundary(params.object("boundary"), s.mesh);
  s.damping = read_damping(params.object("damping"));
  s.receptance = read_receptance(params.object("receptance"), s.mesh);
  read_integrator(params, s);
  const std::string statics_solver = params.object("statics").get<std::string>("solver");
  s.statics_named = statics_solver != "auto";
  s.geometric_statics = statics_solver == "geometric" ||
                        (statics_solver == "auto" && s.mesh.refine >= 1 && s.mesh.file.empty());
  s.aggregation_statics =
      statics_solver == "aggregation" || (statics_solver == "auto" && !s.geometric_statics);
  check_pml_needs(s);
  check_geometric_needs(s);
  return s;
}

}  // namespace rumble::fem
