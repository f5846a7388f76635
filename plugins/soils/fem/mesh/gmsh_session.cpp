// The gmsh session: gmsh keeps global state and reads and writes files of its own, so every use
// of it goes through this one place that sets it up and takes it down the same way.
#include <dlfcn.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mesh/gmsh_model.hpp"

namespace rumble::fem {

namespace {

/// Debian's gmsh links FLTK 1.3 (its GUI), whose first look at one of its options reads and
/// rewrites its preference files, /etc/fltk/fltk.org/fltk.prefs (as root) and
/// ~/.fltk/fltk.org/fltk.prefs (made when missing); gmsh::initialize looks (its default
/// General.Tooltips switches FLTK's tooltips on). Marking FLTK's options as read already keeps it
/// from both; their values matter only to a GUI, which the plugin never opens. Nothing to do
/// where gmsh is built without FLTK.
void keep_fltk_from_its_preference_files() {
  void* fltk = ::dlopen("libfltk.so.1.3", RTLD_LAZY | RTLD_NOLOAD);
  if (fltk == nullptr) return;
  if (auto* read = static_cast<unsigned char*>(::dlsym(fltk, "_ZN2Fl13options_read_E")))
    *read = 1;  // Fl::options_read_
  ::dlclose(fltk);
}

}  // namespace

GmshSession::GmshSession(unsigned threads) {
  keep_fltk_from_its_preference_files();
  // gmsh::initialize appends the executable's folder to PATH and PYTHONPATH (for its ONELAB
  // clients and Python modules, which the plugin never uses) at every session: they grew each
  // time, and glibc keeps every value setenv replaces, so thousands of sessions in one process
  // took memory quadratically (the msh fuzz target ran out of its 2 GiB). Put back as they were,
  // the same values are reused.
  std::vector<std::pair<const char*, std::optional<std::string>>> environment;
  for (const char* name : {"PATH", "PYTHONPATH"}) {
    const char* value = std::getenv(name);
    environment.emplace_back(name,
                             value != nullptr ? std::optional<std::string>(value) : std::nullopt);
  }
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);  // no ~/.gmshrc, ~/.gmsh-options
  for (const auto& [name, value] : environment)
    value ? ::setenv(name, value->c_str(), 1) : ::unsetenv(name);
  // Nothing saved at the end (the GUI's session and options files), and gmsh::finalize removes
  // its temporary file, by default ~/.gmsh-tmp (a user's, from gmsh's GUI): named "." instead,
  // it is the home directory itself, which unlink refuses.
  gmsh::option::setNumber("General.SaveSession", 0);
  gmsh::option::setNumber("General.SaveOptions", 0);
  gmsh::option::setString("General.TmpFileName", ".");
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  gmsh::option::setNumber("General.NumThreads", threads);
  // Same input, same mesh: gmsh otherwise takes as many threads as OpenMP offers per stage.
  for (const char* stage : {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
    gmsh::option::setNumber(stage, threads);
  gmsh::model::add("soil");
}

GmshSession::~GmshSession() {
  gmsh::finalize();
}

}  // namespace rumble::fem
