#pragma once
/// \file
/// Umbrella header of simulation: plants, the closed-loop runner and the
/// series table with its CSV output (brings in `<fstream>`, `<random>` and `<charconv>`).

#include <adaptobs/simulation/continuous_plant.hpp>
#include <adaptobs/simulation/detection_evaluation.hpp>
#include <adaptobs/simulation/discrete_nonlinear_plant.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>
#include <adaptobs/simulation/joint_integration.hpp>
#include <adaptobs/simulation/output_loss.hpp>
#include <adaptobs/simulation/plant.hpp>
#include <adaptobs/simulation/runner.hpp>
#include <adaptobs/simulation/series_table.hpp>
