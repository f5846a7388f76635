// Scenario loading, validation and diagnostics: the one header the CLI needs.
//   load_document -> load_scenario_plugins -> validate -> print_diagnostics
#pragma once

#include "scenario/diagnostic.hpp"
#include "scenario/document.hpp"
#include "scenario/report.hpp"
#include "scenario/scenario_schema.hpp"
#include "scenario/schema_print.hpp"
#include "scenario/validate.hpp"
