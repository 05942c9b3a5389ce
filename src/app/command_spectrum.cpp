#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/limit_options.hpp"
#include "app/record_options.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "io/output_path.hpp"
#include "io/run_file.hpp"
#include "io/instrument_csv.hpp"
#include "io/signal_input.hpp"
#include "io/spectrum_file.hpp"
#include "core/toml_reader.hpp"
#include "pipeline/analyse_spectra.hpp"
#include "pipeline/slip_fraction.hpp"
#include "pipeline/spectral_summary.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc::app {

namespace {

struct SpectrumOptions {
  std::string input;
  std::string out;
  std::string settings_file;
  bool figures = false;
  FigureOptions figure;
  LimitOptions limits;
  RecordOptions record;
};

//! The [spectrum] table of a study file, or the defaults.
SpectrumSettings settings_from(const std::string& file) {
  if (file.empty()) return {};
  // Only [spectrum] is this command's business; the rest of a study file is not checked.
  return read_spectrum_table(*TomlDocument::from_file(file), ": --settings needs a file with a [spectrum] table");
}

void run(const SpectrumOptions& options) {
  check_output_path(options.out, {{options.input, "the signal file"}, {options.settings_file, "the settings file"}});
  const SpectrumSettings settings = settings_from(options.settings_file);
  const bool csv = is_record_text(options.input, options.record.read());
  // A text record of S bytes holds at most S/4 samples (`0,0` and a line end; a Rigol row of
  // index and voltage is no shorter): bound what reading it may cost first.
  if (csv)
    check_work(estimate_spectrum(static_cast<double>(check_input_file(options.input, "the signal CSV file")) / 4.0, 0.0,
                                 settings),
               options.limits.limits(), options.input + ": reading it");
  const RecordReadOptions how = options.record.read();
  const SignalInput signal = csv                        ? read_record_text(options.input, how)
                             : !how.hdf5.dataset.empty() ? read_hdf5_record(options.input, how.hdf5)
                                                         : read_signal_hdf5(options.input);
  check_work(estimate_spectrum(static_cast<double>(signal.times_s.size()), static_cast<double>(signal.currents_a.size()),
                               settings),
             options.limits.limits(), options.input + ": the analysis");
  SpectralInput input;
  input.times_s = signal.times_s;
  input.voltage_v = signal.voltage_v;
  if (!signal.currents_a.empty()) input.currents_a = &signal.currents_a;
  input.expected_frequency_hz = signal.expected_frequency_hz;
  SpectralResult result;
  try {
    // The same sliding rule over the same interval as `run` (pipeline/slip_fraction.hpp).
    if (!signal.expected_frequency_hz.empty()) {
      const AnalysisRange range = analysis_range(input.times_s, settings);
      const SlidingRule rule{signal.model1, signal.belt_velocity_m_per_s, signal.sharpness_s_per_m};
      for (const auto& v : signal.velocity_m_per_s) {
        const std::size_t first = std::min(range.first_sample, v.size());
        const std::span<const double> interval(v.data() + first, std::min(range.samples, v.size() - first));
        input.sliding.push_back(slip_fraction(rule, interval) >= settings.min_slip_fraction);
      }
    }
    result = analyse_spectra(input, settings);
  } catch (const InputError& e) {
    throw InputError(options.input + ": " + e.what());
  }
  Hdf5Writer file(options.out, describe_output);
  Provenance provenance;
  provenance.file_type = "stengmc-spectrum";
  provenance.input_file = options.input;
  write_provenance(file, provenance);
  file.attribute("/", "settings_file", options.settings_file);
  write_spectra(file, result, settings);
  file.commit();
  std::printf("stengmc spectrum %s\n%s", options.input.c_str(), format_spectral_summary(result).c_str());
  if (signal.expected_frequency_hz.empty())
    std::printf("(no /asperity/natural_frequency in the input: identifiability not assessed)\n");
  std::printf("wrote %s\n", options.out.c_str());
  if (options.figures && render_figures(options.out, options.figure) != 0) throw Error("figure rendering failed; the HDF5 output is complete");
}

}  // namespace

void add_spectrum_command(CLI::App& app) {
  auto options = std::make_shared<SpectrumOptions>();
  CLI::App* command = app.add_subcommand(
      "spectrum", "Spectra, peaks, ESPRIT lines, identifiability and spectrogram of an existing output file or a CSV `t,V`");
  command->add_option("input", options->input, "A stengmc output file (uses /time, /circuit/voltage, ...), IN.csv `t,V` or an oscilloscope export (--format)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (/spectrum, /spectrogram)")
      ->required()
      ->check(non_empty_path());
  command->add_option("-s,--settings", options->settings_file, "A study or TOML file whose [spectrum] table to use (default: the defaults)")
      ->check(CLI::ExistingFile);
  CLI::Option* figures = command->add_flag("-f,--figures", options->figures, "Also render figures");
  add_figure_options(command, figures, options->figure);
  add_limit_options(command, options->limits);
  add_record_options(command, options->record);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
