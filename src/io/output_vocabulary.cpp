#include "io/output_vocabulary.hpp"

#include <fnmatch.h>

#include <array>
#include <optional>
#include <sstream>
#include <string_view>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "ensemble/realisation_record.hpp"

namespace stengmc {

namespace {

//! One row of the vocabulary. `path` is a glob (fnmatch, `*` also matching `/`): the
//! first row that matches a dataset's path describes it. `dimensions` are the axis names,
//! space-separated, outermost first; a dataset named as its only dimension is that
//! dimension's coordinate. Units: SI as UDUNITS-2 parses them (CF 1.10, 3.1), "1" for
//! counts, ratios, flags, indices and text, DECIBEL for decibels; "" for a dataset with no
//! single unit, whose `comment` then gives the unit of each part (no units attribute is
//! written: any one would be false for some of its values).
struct Term {
  std::string_view path;
  std::string_view units;
  std::string_view long_name;
  std::string_view dimensions;
  std::string_view comment = {};
};

//! A level in decibels of a power ratio, 10 log10(P/P0), as UDUNITS-2 spells it: it
//! defines no "dB", and "0.1 lg(re 1)" converts 30 to a ratio of 1000.
constexpr std::string_view DECIBEL = "0.1 lg(re 1)";
constexpr std::string_view DECIBEL_COMMENT = "decibels of a power ratio, 10 log10(P_signal/P_noise)";
//! The law parameters' units depend on the law's family (and the bank's on its prior's).
constexpr std::string_view FIRST_UNITS = "median [N/m] for a lognormal law, shape [1] for gamma and weibull";
constexpr std::string_view SECOND_UNITS = "sigma_log [1] for a lognormal law, scale [N/m] for gamma and weibull";
//! The tracking file's track x window tables mark what is absent with NaN.
constexpr std::string_view TRACK_GAPS = "NaN where the track's asperity is not in contact";
constexpr std::string_view LINE_GAPS = "NaN where the track's line was not heard (or after its release)";
constexpr std::string_view PARAMETER_UNITS = "each column in the unit of its parameter (the study key's unit)";

// The dimensions, one name per axis kind across the files:
//   time               sample instants (/time; a trace's own time)
//   window_time        spectrogram segment centres (/spectrogram/window_time)
//   valid_time         the leading samples of /time a flagged run's circuit reached
//                      ("time|valid_time": time when the circuit spans all of /time)
//   asperity           asperities of a realisation, or of all realisations in turn
//   summit             summits drawn, all realisations in turn
//   realisation        realisations (coordinate: their ids where the file has them)
//   realisation_boundary, record_boundary   offsets: one more than realisations/records
//   frequency          spectrum bins; peak, line: detected peaks and ESPRIT lines
//   event              stick/slip events; grid_point: sweep points (an ensemble file names
//                      it after a lone swept key, io/ensemble_coordinates); parameter:
//                      swept or drawn parameters (coordinate: their names)
//   record             inverse: records (measured signals) or calibration records
//   track, event, segment, wear  tracking: tracks, their events, stiffness segments and wear fits
constexpr std::array TERMS{
    // run file (and `circuit` file): the realisation
    Term{"/time", "s", "time", "time"},
    Term{"/valid_time", "s", "time of the samples the circuit of a flagged run reached", "valid_time"},
    Term{"/asperity/k", "N/m", "asperity tangential stiffness", "asperity"},
    Term{"/asperity/m", "kg", "asperity effective mass", "asperity"},
    Term{"/asperity/N", "N", "asperity normal load", "asperity"},
    Term{"/asperity/h", "m", "asperity summit height", "asperity"},
    Term{"/asperity/phi", "rad", "asperity drive phase", "asperity"},
    Term{"/asperity/onset", "s", "asperity contact onset", "asperity"},
    Term{"/asperity/release", "s", "asperity release from contact (the run's end if never released)", "asperity"},
    Term{"/asperity/released", "1", "1 when the asperity is released before the run's end", "asperity"},
    Term{"/asperity/wear_rate", "1/ms", "asperity stiffness wear rate", "asperity"},
    Term{"/asperity/step_count", "1", "number of stiffness steps of the asperity (CF ragged count)", "asperity"},
    Term{"/step/time", "s", "time of a stiffness step", "step"},
    Term{"/step/factor", "1", "stiffness after the step over before", "step"},
    Term{"/asperity/sigma", "C/m^2", "triboelectric charge density of the S-TENG element", "asperity"},
    Term{"/asperity/d0", "m", "effective dielectric thickness of the element", "asperity"},
    Term{"/asperity/w", "m", "element width", "asperity"},
    Term{"/asperity/l", "m", "element length", "asperity"},
    Term{"/asperity/x", "m", "asperity tangential displacement", "asperity time"},
    Term{"/asperity/v", "m/s", "asperity tangential velocity", "asperity time"},
    Term{"/asperity/friction", "N", "tangential force the asperity transmits", "asperity time"},
    Term{"/asperity/x0", "m", "imposed drive displacement (Model 1)", "asperity time"},
    Term{"/asperity/current", "A", "element current", "asperity time|valid_time"},
    Term{"/asperity/charge", "C", "element charge", "asperity time|valid_time"},
    Term{"/asperity/natural_frequency", "Hz", "asperity natural frequency", "asperity"},
    Term{"/asperity/slip_fraction", "1", "fraction of the analysed samples the asperity slides", "asperity"},
    Term{"/asperity/max_x_over_l", "1", "largest displacement over the element length", "asperity"},
    Term{"/asperity/rms_velocity", "m/s", "rms asperity velocity", "asperity"},
    Term{"/asperity/solver_steps", "1", "integrator steps taken", "asperity"},
    Term{"/circuit/voltage", "V", "load voltage", "time|valid_time"},
    Term{"/circuit/charge", "C", "charge delivered to the load resistor", "time|valid_time"},
    Term{"/circuit/measured_voltage", "V", "load voltage with measurement noise", "time|valid_time"},
    Term{"/circuit/probes/v_*", "V", "node voltage of the load netlist ([circuit] probes)", "time|valid_time"},
    Term{"/circuit/probes/i_*", "A", "device current of the load netlist ([circuit] probes)", "time|valid_time"},
    Term{"/events/time", "s", "event time", "event"},
    Term{"/events/asperity", "1", "index of the asperity", "event"},
    Term{"/events/kind", "1", "event kind", "event"},
    // spectra (run file and `spectrum` file)
    Term{"/spectrum/frequency", "Hz", "frequency", "frequency"},
    Term{"/spectrum/voltage", "V", "amplitude spectrum of the load voltage", "frequency"},
    Term{"/spectrum/current", "A", "amplitude spectrum of each element current", "asperity frequency"},
    Term{"/spectrum/expected_frequency", "Hz", "asperity natural frequency", "asperity"},
    Term{"/spectrum/sliding", "1", "1 when the asperity slides enough to show a line", "asperity"},
    Term{"/spectrum/peaks/frequency", "Hz", "peak frequency", "peak"},
    Term{"/spectrum/peaks/amplitude", "V", "peak amplitude", "peak"},
    Term{"/spectrum/peaks/prominence", "V", "peak prominence", "peak"},
    Term{"/spectrum/lines/frequency", "Hz", "ESPRIT line frequency", "line"},
    Term{"/spectrum/lines/amplitude", "V", "ESPRIT line amplitude", "line"},
    Term{"/spectrum/lines/damping", "1/s", "ESPRIT line damping rate", "line"},
    Term{"/spectrum/lines/phase", "rad", "ESPRIT line phase", "line"},
    Term{"/spectrum/identifiability/*/identified", "1", "1 when a detected line identifies the asperity", "asperity"},
    Term{"/spectrum/identifiability/*/matched_line", "1", "index of the matched peak or line (-1: none)", "asperity"},
    Term{"/spectrum/identifiability/*/frequency_error", "Hz", "matched frequency minus natural frequency (0 unmatched)",
         "asperity"},
    Term{"/spectrum/identifiability/*/amplitude", "V", "amplitude of the matched peak or line (0 unmatched)", "asperity"},
    // Its own axis: a dimension "time" here would shadow the root's for netCDF readers.
    Term{"/spectrogram/window_time", "s", "segment centre time", "window_time"},
    Term{"/spectrogram/frequency", "Hz", "frequency", "frequency"},
    Term{"/spectrogram/voltage", "V", "amplitude spectrum of the load voltage per segment", "window_time frequency"},
    // populations (surface file at /, run file at /surface)
    Term{"/summit", "1", "summit: row of /summits (every realisation's summits in turn)", "summit"},
    Term{"/surface/summit", "1", "summit: row of /surface/summits (every realisation's summits in turn)", "summit"},
    Term{"/asperity", "1", "asperity: row of /asperities (every realisation's asperities in turn)", "asperity"},
    Term{"/surface/asperity", "1", "asperity: row of /surface/asperities (every realisation's asperities in turn)",
         "asperity"},
    Term{"*/realisations/realisation", "1", "realisation id", "realisation"},
    Term{"*/realisations/summit_count", "1", "summits drawn", "realisation"},
    Term{"*/realisations/asperity_count", "1", "summits in contact: the asperities simulated", "realisation"},
    Term{"*/realisations/cannot_slip_model1_count", "1", "Model 1 asperities that cannot slip", "realisation"},
    Term{"*/realisations/near_length_model2_count", "1", "Model 2 asperities breaking away near the element length",
         "realisation"},
    Term{"*/realisations/warnings", "1", "validity warnings", "realisation"},
    Term{"*/realisations/summit_offset", "1", "first summit of each realisation in /summits (and the end)",
         "realisation_boundary"},
    Term{"*/realisations/asperity_offset", "1", "first asperity of each realisation in /asperities (and the end)",
         "realisation_boundary"},
    Term{"*/realisations/separation_m", "m", "mean-plane separation", "realisation"},
    Term{"*/realisations/total_load_n", "N", "total normal load", "realisation"},
    Term{"*/realisations/real_area_m2", "m^2", "real contact area", "realisation"},
    Term{"*/realisations/contact_density", "1", "real contact area over nominal area", "realisation"},
    Term{"*/realisations/screening_estimate", "1", "screening estimate of the spots' interaction", "realisation"},
    Term{"*/realisations/load_redistribution", "1", "fraction of the normal load the spots' interaction moves",
         "realisation"},
    Term{"*/realisations/interaction_rms_relative", "1", "rms interaction displacement over interference", "realisation"},
    Term{"*/realisations/interaction_max_relative", "1", "largest interaction displacement over interference",
         "realisation"},
    Term{"*/realisations/overlapping_pairs", "1", "pairs of overlapping contact patches", "realisation"},
    Term{"*/realisations/independence_holds", "1", "1 when the spots' interaction stays below its threshold",
         "realisation"},
    Term{"*/realisations/interacting_iterations", "1", "fixed-point iterations of the interacting contact", "realisation"},
    Term{"*/realisations/interacting_converged", "1", "1 when the interacting contact converged", "realisation"},
    Term{"*/realisations/load_carried", "1", "1 when the contact carries the nominal load", "realisation"},
    Term{"*/realisations/localisation_radius_m", "m", "interaction localisation radius", "realisation"},
    Term{"*/realisations/far_field_m", "m", "interaction far-field displacement", "realisation"},
    Term{"*/summits/height_m", "m", "summit height", "summit"},
    Term{"*/summits/x_m", "m", "summit x position", "summit"},
    Term{"*/summits/y_m", "m", "summit y position", "summit"},
    Term{"*/summits/drive_phase_rad", "rad", "summit drive phase", "summit"},
    Term{"*/summits/onset_s", "s", "summit contact onset", "summit"},
    Term{"*/summits/lifetime_s", "s", "summit contact lifetime (release - onset)", "summit"},
    Term{"*/summits/wear_rate_per_ms", "1/ms", "summit stiffness wear rate", "summit"},
    Term{"*/summits/step_time_s", "s", "time of the summit's stiffness step (its onset plus the drawn delay)", "summit"},
    Term{"*/summits/step_factor", "1", "summit stiffness after its step over before (1: no step)", "summit"},
    Term{"*/summits/normal_load_n", "N", "summit normal load", "summit"},
    Term{"*/summits/sampled_stiffness_n_per_m", "N/m", "sampled tangential stiffness", "summit"},
    Term{"*/summits/interference_m", "m", "summit interference", "summit"},
    Term{"*/summits/patch_radius_m", "m", "contact patch radius", "summit"},
    Term{"*/summits/extra_displacement_m", "m", "displacement the other spots add", "summit"},
    Term{"*/summits/interaction_relative", "1", "interaction displacement over interference", "summit"},
    Term{"*/asperities/summit_index", "1", "index of the asperity's summit in its realisation", "asperity"},
    Term{"*/asperities/stiffness_n_per_m", "N/m", "asperity tangential stiffness", "asperity"},
    Term{"*/asperities/mass_kg", "kg", "asperity effective mass", "asperity"},
    Term{"*/asperities/normal_load_n", "N", "asperity normal load", "asperity"},
    Term{"*/asperities/height_m", "m", "asperity summit height", "asperity"},
    Term{"*/asperities/element_length_m", "m", "element length", "asperity"},
    Term{"*/asperities/element_width_m", "m", "element width", "asperity"},
    Term{"*/asperities/drive_phase_rad", "rad", "asperity drive phase", "asperity"},
    Term{"*/asperities/onset_s", "s", "asperity contact onset", "asperity"},
    Term{"*/asperities/cannot_slip_model1", "1", "1 when the asperity cannot slip under Model 1", "asperity"},
    Term{"*/asperities/static_deflection_over_length", "1", "static deflection over the element length", "asperity"},
    Term{"*/asperities/near_length_model2", "1", "1 when Model 2 breaks away near the element length", "asperity"},
    // surface file
    Term{"/target/heights/value", "m", "height", "value"},
    Term{"/target/heights/density", "1/m", "target height density (probability for a discrete law)", "value"},
    Term{"/target/stiffness/value", "N/m", "stiffness", "value"},
    Term{"/target/stiffness/density", "m/N", "target stiffness density (probability for a discrete law)", "value"},
    Term{"/load_separation/separation_m", "m", "mean-plane separation", "separation_m"},
    Term{"/load_separation/total_load_n", "N", "total normal load at the separation", "separation_m"},
    // ensemble file (its scalars and asperity columns: describe_ensemble below)
    Term{"/grid/parameter", "1", "swept parameter", "parameter"},
    Term{"/grid/values", "", "value of each swept parameter", "grid_point parameter", PARAMETER_UNITS},
    Term{"/realisations/grid_point", "1", "grid point of the realisation", "realisation"},
    Term{"/realisations/valid", "1", "1 when the realisation is valid", "realisation"},
    Term{"/realisations/failure", "1", "why the realisation is invalid", "realisation"},
    Term{"/draws/parameter", "1", "drawn parameter", "parameter"},
    Term{"/draws/values", "", "value drawn for each parameter", "realisation parameter", PARAMETER_UNITS},
    Term{"/traces/*/time", "s", "time", "time"},
    Term{"/traces/*/voltage", "V", "load voltage", "time"},
    Term{"/traces/*/charge", "C", "charge delivered to the load resistor", "time"},
    Term{"/traces/*/measured_voltage", "V", "load voltage with measurement noise", "time"},
    // Its units are the target statistic's where there is one (io/ensemble_file.cpp).
    Term{"/summary/target/half_width", "", "half-width reached by the target statistic", "grid_point",
         "in the unit of the target statistic (root attribute target_statistic); 0 without one"},
    Term{"/summary/target/met", "1", "1 when the target half-width was met", "grid_point"},
    // inverse result file
    Term{"/inverse/records/name", "1", "record name", "record"},
    Term{"/inverse/records/noise_sigma_v", "V", "noise standard deviation", "record"},
    Term{"/inverse/records/residual_sigma_v", "V", "residual standard deviation of the fit", "record"},
    Term{"/inverse/records/signal_to_noise_db", DECIBEL, "signal-to-noise ratio", "record", DECIBEL_COMMENT},
    Term{"/inverse/records/band_power_ratio", "1", "fraction of the power in the prior's band", "record"},
    Term{"/inverse/records/lines_outside_prior", "1", "lines outside the prior's band", "record"},
    Term{"/inverse/records/onset_steps", "1", "contact onsets the record shows as steps", "record"},
    Term{"/inverse/records/seconds", "s", "computing time", "record"},
    Term{"/inverse/records/verdict", "1", "verdict", "record"},
    Term{"/inverse/records/warnings", "1", "warnings", "record"},
    Term{"/inverse/count/counts", "1", "asperity count", "counts"},
    Term{"/inverse/count/estimate", "1", "estimated asperity count", "record"},
    Term{"/inverse/count/interval_low", "1", "lower end of the count's interval", "record"},
    Term{"/inverse/count/interval_high", "1", "upper end of the count's interval", "record"},
    Term{"/inverse/count/naive_fft", "1", "naive FFT peak count", "record"},
    Term{"/inverse/count/probability", "1", "calibrated probability of each count", "record counts"},
    Term{"/inverse/count/raw_probability", "1", "uncalibrated posterior probability of each count", "record counts"},
    Term{"/inverse/lines/record", "1", "index of the line's record", "line"},
    Term{"/inverse/lines/stiffness_n_per_m", "N/m", "estimated stiffness", "line"},
    Term{"/inverse/lines/stiffness_low", "N/m", "lower end of the stiffness interval", "line"},
    Term{"/inverse/lines/stiffness_high", "N/m", "upper end of the stiffness interval", "line"},
    Term{"/inverse/lines/log_stiffness_se", "1", "standard error of the log stiffness", "line"},
    Term{"/inverse/lines/se_inflation", "1", "log stiffness error over its value were the other lines known", "line"},
    Term{"/inverse/lines/frequency_hz", "Hz", "line frequency", "line"},
    Term{"/inverse/lines/amplitude_v", "V", "line amplitude", "line"},
    Term{"/inverse/lines/nearest_separation_hz", "Hz", "distance to the nearest other line", "line"},
    Term{"/inverse/lines/offset", "1", "first line of each record (and the end)", "record_boundary"},
    Term{"/inverse/stiffness/median", "N/m", "population median stiffness", "record"},
    Term{"/inverse/stiffness/median_low", "N/m", "lower end of the median's interval", "record"},
    Term{"/inverse/stiffness/median_high", "N/m", "upper end of the median's interval", "record"},
    Term{"/inverse/stiffness/sd_log", "1", "population standard deviation of log stiffness", "record"},
    Term{"/inverse/stiffness/sd_log_low", "1", "lower end of sd_log's interval", "record"},
    Term{"/inverse/stiffness/sd_log_high", "1", "upper end of sd_log's interval", "record"},
    Term{"/inverse/stiffness/intervals_calibrated", "1", "1 when the intervals are calibrated", "record"},
    Term{"/inverse/*/laws/record", "1", "index of the law's record", "law"},
    Term{"/inverse/*/laws/family", "1", "stiffness law family", "law"},
    Term{"/inverse/*/laws/fitted", "1", "1 when the law was fitted", "law"},
    Term{"/inverse/*/laws/first", "", "first law parameter", "law", FIRST_UNITS},
    Term{"/inverse/*/laws/first_low", "", "lower end of the first parameter's interval", "law", FIRST_UNITS},
    Term{"/inverse/*/laws/first_high", "", "upper end of the first parameter's interval", "law", FIRST_UNITS},
    Term{"/inverse/*/laws/second", "", "second law parameter", "law", SECOND_UNITS},
    Term{"/inverse/*/laws/second_low", "", "lower end of the second parameter's interval", "law", SECOND_UNITS},
    Term{"/inverse/*/laws/second_high", "", "upper end of the second parameter's interval", "law", SECOND_UNITS},
    Term{"/inverse/*/laws/aic", "1", "Akaike information criterion", "law"},
    Term{"/inverse/*/laws/delta_aic", "1", "AIC minus the record's best", "law"},
    Term{"/inverse/*/laws/median", "N/m", "law median stiffness", "law"},
    Term{"/inverse/*/laws/sd_log", "1", "law standard deviation of log stiffness", "law"},
    Term{"/inverse/traces/*/time", "s", "time", "time"},
    Term{"/inverse/traces/*/voltage", "V", "recorded voltage", "time"},
    Term{"/inverse/traces/*/model", "V", "fitted record model", "time"},
    // tracking file (`stengmc track`)
    Term{"/tracking/window_time", "s", "window centre time", "window_time"},
    Term{"/tracking/window_start", "s", "time of the window's first sample", "window_time"},
    Term{"/tracking/window_mean", "V", "mean voltage of the window (the plateau)", "window_time"},
    Term{"/tracking/noise_floor", "V", "noise level the window's lines were judged against", "window_time"},
    Term{"/tracking/count", "1", "asperities in contact (tracks)", "window_time"},
    Term{"/tracking/count_low", "1", "lower end of the count's 90 % interval", "window_time"},
    Term{"/tracking/count_high", "1", "upper end of the count's 90 % interval", "window_time"},
    Term{"/tracking/naive_count", "1", "naive FFT peak count of the window", "window_time"},
    Term{"/tracking/track", "1", "track index", "track"},
    Term{"/tracking/error_inflation", "1", "factor the track's Cramer-Rao errors were scaled by to its scatter", "track"},
    Term{"/tracking/stiffness_n_per_m", "N/m", "stiffness of the track's asperity", "track window_time", TRACK_GAPS},
    Term{"/tracking/stiffness_low", "N/m", "lower end of the stiffness's 90 % interval", "track window_time", TRACK_GAPS},
    Term{"/tracking/stiffness_high", "N/m", "upper end of the stiffness's 90 % interval", "track window_time", TRACK_GAPS},
    Term{"/tracking/frequency_hz", "Hz", "frequency of the track's line", "track window_time", LINE_GAPS},
    Term{"/tracking/frequency_low", "Hz", "lower end of the frequency's 90 % interval", "track window_time", LINE_GAPS},
    Term{"/tracking/frequency_high", "Hz", "upper end of the frequency's 90 % interval", "track window_time", LINE_GAPS},
    Term{"/tracking/events/kind", "1", "event kind (onset, release, step)", "event"},
    Term{"/tracking/events/time_s", "s", "event time", "event"},
    Term{"/tracking/events/time_low_s", "s", "earliest time the windows allow", "event"},
    Term{"/tracking/events/time_high_s", "s", "latest time the windows allow", "event"},
    Term{"/tracking/events/track", "1", "index of the event's track", "event"},
    Term{"/tracking/segments/track", "1", "index of the segment's track", "segment"},
    Term{"/tracking/segments/start_s", "s", "first window centre of the segment", "segment"},
    Term{"/tracking/segments/end_s", "s", "last window centre of the segment", "segment"},
    Term{"/tracking/segments/windows", "1", "windows averaged", "segment"},
    Term{"/tracking/segments/stiffness_n_per_m", "N/m", "stiffness between two events of the track", "segment"},
    Term{"/tracking/segments/stiffness_low", "N/m", "lower end of its 90 % interval", "segment"},
    Term{"/tracking/segments/stiffness_high", "N/m", "upper end of its 90 % interval", "segment"},
    Term{"/tracking/segments/frequency_hz", "Hz", "mean frequency of the segment", "segment"},
    Term{"/tracking/wear/track", "1", "index of the track whose wear was fitted", "wear"},
    Term{"/tracking/wear/wear_rate_per_ms", "1/ms", "wear rate: stiffness lost per ms over the stiffness at the track's start", "wear"},
    Term{"/tracking/wear/wear_rate_low", "1/ms", "lower end of the wear rate's 90 % interval", "wear"},
    Term{"/tracking/wear/wear_rate_high", "1/ms", "upper end of the wear rate's 90 % interval", "wear"},
    Term{"/tracking/wear/pieces", "1", "pieces of 4 tau whose line centres the slope was fitted to", "wear"},
    Term{"/tracking/lines/window", "1", "index of the line's window", "line"},
    Term{"/tracking/lines/frequency_hz", "Hz", "line frequency (ESPRIT; excited: periodogram peak)", "line"},
    Term{"/tracking/lines/frequency_se_hz", "Hz", "standard error of the frequency (Cramer-Rao; excited: the peak's wander)", "line"},
    Term{"/tracking/lines/amplitude_v", "V", "line amplitude at the window's first sample", "line"},
    Term{"/tracking/lines/snr", "1", "matched-filter amplitude signal-to-noise ratio", "line"},
    Term{"/tracking/lines/detected", "1", "1 when above the detection threshold (else a candidate)", "line"},
    Term{"/tracking/record/time", "s", "time", "time"},
    Term{"/tracking/record/voltage", "V", "recorded voltage", "time"},
    // calibration bank
    Term{"/atoms/pi_nodes", "1", "Pi of each node of the shape family (belt-carried stretch, rad)", "pi_node"},
    Term{"/atoms/zeta_nodes", "1", "zeta of each node (damping ratio)", "zeta_node"},
    Term{"/atoms/onset_nodes", "1", "nodes holding an onset-aligned shape (index pi x zeta)", "onset_node"},
    Term{"/atoms/onset_values", "1", "x'/v_b from the onset, the viscous decay divided out", "onset_node theta_sample"},
    Term{"/atoms/onset_slopes", "1", "d/dtheta of onset_values", "onset_node theta_sample"},
    Term{"/atoms/breakaway_nodes", "1", "nodes holding a breakaway-aligned shape (index pi x zeta)", "breakaway_node"},
    Term{"/atoms/breakaway_values", "1", "x'/v_b about the breakaway, the viscous decay divided out", "breakaway_node psi_sample"},
    Term{"/atoms/breakaway_slopes", "1", "d/dtheta of breakaway_values", "breakaway_node psi_sample"},
    Term{"/atoms/breakaway_share", "1", "friction share where the breakaway piece starts, per node", "node"},
    Term{"/atoms/tail_log_amplitude", "1", "-ln of the tail's envelope where it starts (viscous part out), per node", "node"},
    Term{"/atoms/tail_phase", "rad", "phase of the tail, per node", "node"},
    Term{"/maps/fits/confusion", "1", "P(true count | estimated count), records whose fit explains them to their noise", "estimated_count count"},
    Term{"/maps/fits/median_score_quantile", "1", "conformal quantile of the median's score per count bin, records whose fit explains them to their noise", "count_bin"},
    Term{"/maps/fits/sd_score_quantile", "1", "conformal quantile of sd_log's score per count bin, records whose fit explains them to their noise", "count_bin"},
    Term{"/maps/misfits/confusion", "1", "P(true count | estimated count), records whose fit does not explain them to their noise", "estimated_count count"},
    Term{"/maps/misfits/median_score_quantile", "1", "conformal quantile of the median's score per count bin, records whose fit does not explain them to their noise", "count_bin"},
    Term{"/maps/misfits/sd_score_quantile", "1", "conformal quantile of sd_log's score per count bin, records whose fit does not explain them to their noise", "count_bin"},
    Term{"/maps/naive_thresholds", "1", "naive count thresholds, in multiples of the local noise floor", "threshold"},
    Term{"/records/realisation", "1", "realisation id", "realisation"},
    Term{"/records/valid", "1", "1 when the record is valid", "realisation"},
    Term{"/records/true_count", "1", "true asperity count", "realisation"},
    Term{"/records/count", "1", "estimated asperity count", "realisation"},
    Term{"/records/snr_db", DECIBEL, "signal-to-noise ratio drawn", "realisation", DECIBEL_COMMENT},
    Term{"/records/law_first", "", "first parameter of the drawn law", "realisation", FIRST_UNITS},
    Term{"/records/law_second", "", "second parameter of the drawn law", "realisation", SECOND_UNITS},
    Term{"/records/true_median", "N/m", "true median stiffness", "realisation"},
    Term{"/records/median", "N/m", "estimated median stiffness", "realisation"},
    Term{"/records/true_sd_log", "1", "true standard deviation of log stiffness", "realisation"},
    Term{"/records/sd_log", "1", "estimated standard deviation of log stiffness", "realisation"},
    Term{"/records/noise_sigma", "V", "noise standard deviation", "realisation"},
    Term{"/records/residual_sigma", "V", "residual standard deviation of the fit", "realisation"},
    Term{"/records/band_power_ratio", "1", "fraction of the power in the prior's band", "realisation"},
    Term{"/records/snr_estimate_db", DECIBEL, "estimated signal-to-noise ratio", "realisation", DECIBEL_COMMENT},
    Term{"/records/seconds", "s", "computing time", "realisation"},
    Term{"/records/naive_count", "1", "naive count at the chosen threshold", "realisation"},
    Term{"/records/naive_counts", "1", "naive count at each threshold", "realisation threshold"},
    Term{"/records/true_stiffness", "N/m", "true stiffness, all records in turn", "true_line"},
    Term{"/records/true_offset", "1", "first true stiffness of each record (and the end)", "realisation_boundary"},
    Term{"/records/stiffness", "N/m", "estimated stiffness, all records in turn", "line"},
    Term{"/records/log_stiffness_se", "1", "standard error of the log stiffness", "line"},
    Term{"/records/estimate_offset", "1", "first estimate of each record (and the end)", "realisation_boundary"},
    Term{"/records/orders", "1", "model order tried, all records in turn", "order"},
    Term{"/records/log_evidence", "1", "log evidence of each order", "order"},
    Term{"/records/order_offset", "1", "first order of each record (and the end)", "realisation_boundary"},
};

std::vector<std::string> split(std::string_view words) {
  std::vector<std::string> out;
  std::istringstream in{std::string(words)};
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

//! Ensemble files name their per-realisation scalars and asperity columns after the
//! ensemble's own table (ensemble/realisation_record.hpp), and summarise each scalar in
//! /summary/<scalar>/<statistic>[_low|_high|_known|_method] over its grid points.
std::optional<DatasetDescription> describe_ensemble(const std::string& path) {
  auto scalar = [](std::string_view name) -> const ScalarInfo* {
    Scalar s{};
    return scalar_by_name(name, s) ? &scalar_info(s) : nullptr;
  };
  constexpr std::string_view realisations = "/realisations/", asperities = "/asperities/", summary = "/summary/";
  if (path.starts_with(realisations))
    if (const ScalarInfo* info = scalar(path.substr(realisations.size())))
      return DatasetDescription{std::string(info->unit), std::string(info->long_name), {"realisation"}};
  if (path.starts_with(asperities))
    for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
      if (const ScalarInfo& info = column_info(static_cast<AsperityColumn>(c)); info.name == path.substr(asperities.size()))
        return DatasetDescription{std::string(info.unit), std::string(info.long_name), {"asperity"}};
  if (!path.starts_with(summary)) return std::nullopt;
  const std::size_t slash = path.find('/', summary.size());
  if (slash == std::string::npos) return std::nullopt;
  const std::string group = path.substr(summary.size(), slash - summary.size());
  std::string statistic = path.substr(slash + 1);
  std::string unit, quantity;
  if (const ScalarInfo* info = scalar(group)) {
    unit = info->unit;
    quantity = info->long_name;
  } else if (group == "pooled") {
    unit = "1";
    quantity = statistic.starts_with("fft_ratio")  ? "pooled FFT identification ratio"
               : statistic.starts_with("hr_ratio") ? "pooled ESPRIT identification ratio"
                                                   : "fraction of valid realisations";
  } else {
    return std::nullopt;
  }
  std::string part = "";
  for (const auto& [suffix, words, unitless] :
       {std::tuple{"_low", "lower end of the interval of ", false}, {"_high", "upper end of the interval of ", false},
        {"_known", "1 when the interval is a confidence interval: ", true},
        {"_method", "method of the interval of ", true}}) {
    const std::string_view s(suffix);
    if (statistic.size() > s.size() && statistic.ends_with(s)) {
      statistic.resize(statistic.size() - s.size());
      part = words;
      if (unitless) unit = "1";
      break;
    }
  }
  if (statistic == "count") unit = "1";
  const std::string what = group == "pooled" ? quantity : statistic + " of " + quantity + " over valid realisations";
  return DatasetDescription{unit, part + what, {"grid_point"}};
}

}  // namespace

DatasetDescription describe_output(const std::string& path) {
  for (const Term& term : TERMS)
    if (fnmatch(std::string(term.path).c_str(), path.c_str(), 0) == 0)
      return {std::string(term.units), std::string(term.long_name), split(term.dimensions), std::string(term.comment)};
  if (auto described = describe_ensemble(path)) return *described;
  throw Error("no description of the output dataset " + path + " (add it to io/output_vocabulary.cpp)");
}

}  // namespace stengmc
