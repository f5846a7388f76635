// Calibration of a reduced soil's parameters against a target soil's receptance: Levenberg-
// Marquardt on the logarithms of the (positive) parameters, minimising the complex receptance
// misfit at the footprints over a frequency band. Generic over soil plugins: each trial is a
// new instance of the model type with the candidate params, read through frequency_response.
#pragma once

#include <rumble/abi.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/soil_frf.hpp"
#include "plugin/registry.hpp"

namespace rumble {

struct CalibrationProblem {
  const ComponentType* model = nullptr;  // soil type to fit
  nlohmann::json base_params;            // its params; the fitted keys are overwritten
  std::vector<std::string> fit;          // names of the params to fit (each > 0)
  std::vector<rumble_footprint> layout;  // footprints
  SoilFrf target;                        // what to match (same frequencies and terms)
  std::filesystem::path scenario_dir;
};

struct CalibrationResult {
  nlohmann::json params;      // base_params with the fitted values
  double relative_rms = 0.0;  // sqrt(mean |H - H_target|^2 / |H_target,driving|^2)
  int iterations = 0;
  bool converged = false;
};

/// The receptance misfit for a given params object (relative RMS, see CalibrationResult).
double receptance_misfit(const CalibrationProblem& problem, const nlohmann::json& params);

CalibrationResult calibrate(const CalibrationProblem& problem);

}  // namespace rumble
