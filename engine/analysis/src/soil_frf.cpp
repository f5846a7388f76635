#include "analysis/soil_frf.hpp"

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/number_text.hpp"
#include "plugin/instance.hpp"
#include "results/csv_file.hpp"

namespace rumble {

std::vector<double> log_frequencies(double f_min, double f_max, int n_points) {
  std::vector<double> f(static_cast<std::size_t>(std::max(n_points, 1)));
  const double ratio = n_points > 1 ? std::log(f_max / f_min) / (n_points - 1) : 0.0;
  for (std::size_t j = 0; j < f.size(); ++j)
    f[j] = f_min * std::exp(ratio * static_cast<double>(j));
  return f;
}

bool soil_frf(SoilInstance& soil, std::size_t n, const std::vector<double>& frequency,
              std::size_t transfer_terms, SoilFrf& frf) {
  frf.centre = n / 2;
  const std::size_t terms = std::min(transfer_terms + 1, n - frf.centre);
  frf.frequency = frequency;
  frf.receptance.assign(terms, std::vector<std::complex<double>>(frequency.size()));
  std::vector<std::complex<double>> h;
  // Ctrl-C is looked for between frequencies and honoured inside one by soils that check for it
  // (the FEM soil's impulse runs): either way the user learns where it stopped.
  const auto interrupted = [&](std::size_t j) {
    return Interrupted("interrupted (" + std::string(interrupt_cause()) + ") while soil '" +
                       soil.type_name() + "' computed its receptance at " +
                       number_text(frequency[j]) + " Hz, " + std::to_string(j) + " of " +
                       std::to_string(frequency.size()) +
                       " frequencies done; files already written stay, and a soil that caches "
                       "its receptance (fem) keeps each frequency it finished, so the same "
                       "command picks up from there");
  };
  for (std::size_t j = 0; j < frequency.size(); ++j) {
    if (interrupt_requested()) throw interrupted(j);
    try {
      if (!soil.frequency_response(frequency[j], n, h)) {
        frf.receptance.clear();
        return false;
      }
    } catch (const RunError&) {
      if (interrupt_requested()) throw interrupted(j);  // the plugin stopped at the request
      throw;
    }
    for (std::size_t k = 0; k < terms; ++k)
      frf.receptance[k][j] = h[(frf.centre + k) + n * frf.centre];  // column-major (row, col)
  }
  return true;
}

void write_frf_csv(const std::filesystem::path& file, const SoilFrf& frf) {
  std::vector<std::string> columns{"f [Hz]"};
  for (std::size_t k = 0; k < frf.receptance.size(); ++k) {
    const std::string term = k == 0 ? "driving point" : "transfer +" + std::to_string(k);
    columns.push_back(frf.label + " " + term + " |H| [m/N]");
    columns.push_back(frf.label + " " + term + " phase [deg]");
  }
  CsvFile csv(file, columns);
  std::vector<double> row(2 * frf.receptance.size());
  for (std::size_t j = 0; j < frf.frequency.size(); ++j) {
    for (std::size_t k = 0; k < frf.receptance.size(); ++k) {
      row[2 * k] = std::abs(frf.receptance[k][j]);
      row[2 * k + 1] = std::arg(frf.receptance[k][j]) * 180.0 / std::numbers::pi;
    }
    csv.row(frf.frequency[j], row.data(), row.size());
  }
}

}  // namespace rumble
