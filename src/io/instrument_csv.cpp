#include "io/instrument_csv.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/text_excerpt.hpp"
#include "io/record_units.hpp"
#include "spectral/analysed_voltage.hpp"

namespace stengmc {

namespace {

//! Lines read to recognise a layout: every preamble below is shorter (a Tektronix MSO's, the
//! longest, has about 25 lines).
constexpr std::size_t HEAD_LINES = 64;

using Fields = std::vector<std::string>;

//! Where the samples are in a file, and in which units.
struct Layout {
  std::size_t data_line = 0;          //!< index (from 0) of the first line of samples
  Fields names;                       //!< column names, by column
  Fields units;                       //!< column units as written ("" = SI)
  std::size_t units_line = 1;         //!< line (from 1) the units were read from, for messages
  std::size_t time_column = 0;
  bool time_from_index = false;       //!< Rigol: the column counts samples; t = start + index * increment
  double start_s = 0.0;               //!< with time_from_index
  double increment_s = 0.0;           //!< with time_from_index
  std::vector<std::size_t> channels;  //!< the columns that hold voltages
};

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what) {
  throw InputError(path + ":" + std::to_string(line) + ": " + what);
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

bool same_letters(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

//! The trimmed fields of `line`, quotes around a field removed. Tektronix and Rigol end each
//! line with a delimiter: an empty last column is no column.
Fields split(std::string_view line, char delimiter) {
  Fields fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = line.find(delimiter, begin);
    std::string field = trim_blanks(line.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin));
    if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = field.substr(1, field.size() - 2);
    fields.push_back(std::move(field));
    if (end == std::string_view::npos) break;
    begin = end + 1;
  }
  while (!fields.empty() && fields.back().empty()) fields.pop_back();
  return fields;
}

//! Tab, semicolon or comma, judged on the last line read (a line of samples in every layout
//! here): a tab or a semicolon there is the delimiter, since a European export that writes a
//! decimal comma separates its fields by one of them.
char delimiter_of(const std::vector<std::string>& lines) {
  for (auto line = lines.rbegin(); line != lines.rend(); ++line) {
    if (blank(*line)) continue;
    if (line->find('\t') != std::string::npos) return '\t';
    if (line->find(';') != std::string::npos) return ';';
    return ',';
  }
  return ',';
}

//! The first row of the preamble whose first field is `key`, and its index; nothing if none.
std::optional<std::size_t> row_with_key(const std::vector<Fields>& head, std::string_view key) {
  for (std::size_t i = 0; i < head.size(); ++i)
    if (!head[i].empty() && head[i][0] == key) return i;
  return std::nullopt;
}

std::string value_of(const std::vector<Fields>& head, std::string_view key) {
  const auto row = row_with_key(head, key);
  return row && head[*row].size() > 1 ? head[*row][1] : std::string();
}

std::vector<std::size_t> columns_after_time(std::size_t count) {
  std::vector<std::size_t> columns;
  for (std::size_t c = 1; c < count; ++c) columns.push_back(c);
  return columns;
}

//! The row that names the columns, found by its first field `time_name`, and the samples
//! after it; units from the preamble (or SI).
Layout header_row_layout(const std::vector<Fields>& head, std::string_view time_name, const std::string& time_unit,
                         const std::string& voltage_unit, std::size_t units_line) {
  Layout layout;
  for (std::size_t i = 0; i < head.size(); ++i) {
    if (head[i].size() < 2 || !same_letters(head[i][0], time_name)) continue;
    layout.names = head[i];
    layout.data_line = i + 1;
    layout.units.assign(layout.names.size(), voltage_unit);
    layout.units[0] = time_unit;
    layout.units_line = units_line;
    layout.channels = columns_after_time(layout.names.size());
    return layout;
  }
  layout.names.clear();
  return layout;
}

//! Tektronix. The classic TDS1000/TDS2000 CSV ("Save All", TDS2000 series user manual: CSV
//! file format) writes its preamble (Record Length, Sample Interval, Trigger Point, Source,
//! Vertical Units, Horizontal Units, ...) in columns 1-2 and the samples in columns 4-5 of
//! the same lines, from line 1. The MSO/MDO/DPO series write `key,value` preamble lines
//! (Model, ..., Record Length, Sample Interval, Horizontal Units, Vertical Units, ...) and then
//! a header row `TIME,CH1[,CH2...]` above the samples.
Layout tektronix_layout(const std::vector<Fields>& head, const std::string& path) {
  const std::string time_unit = value_of(head, "Horizontal Units");
  const std::string voltage_unit = value_of(head, "Vertical Units");
  const std::size_t units_line = row_with_key(head, "Vertical Units").value_or(0) + 1;
  if (head[0].size() >= 5) {
    Layout layout;
    const std::string source = value_of(head, "Source");
    layout.names = {"", "", "", "TIME", source.empty() ? "CH1" : source};
    layout.units = {"", "", "", time_unit, voltage_unit};
    layout.units_line = units_line;
    layout.time_column = 3;
    layout.channels = {4};
    return layout;
  }
  Layout layout = header_row_layout(head, "TIME", time_unit, voltage_unit, units_line);
  if (layout.names.empty())
    fail(path, 1, "a Tektronix export has samples in columns 4-5 from line 1 (TDS) or a `TIME,CH1` row after its preamble "
                  "(MSO/DPO); neither is in the first " + std::to_string(HEAD_LINES) + " lines");
  return layout;
}

//! The names on line 1, a unit per column on line 2, the samples from line 3 (Keysight and
//! PicoScope); `missing` says what a file without that units row lacks.
Layout header_and_units_layout(const std::vector<Fields>& head, const std::string& path, const std::string& missing) {
  if (head.size() < 2 || head[1].size() != head[0].size()) fail(path, 2, missing);
  Layout layout;
  layout.names = head[0];
  layout.units = head[1];
  layout.units_line = 2;
  layout.data_line = 2;
  layout.channels = columns_after_time(layout.names.size());
  return layout;
}

//! Keysight/Agilent InfiniiVision (2000/3000/4000 X user's guides, "CSV data"): a row of
//! channel numbers `x-axis,1[,2...]`, a units row `second,Volt[,Volt...]`, then the samples.
Layout keysight_layout(const std::vector<Fields>& head, const std::string& path) {
  return header_and_units_layout(head, path, "a Keysight export has a units row (`second,Volt`) with one unit per column of `" +
                                                 text_excerpt(head.empty() || head[0].empty() ? "" : head[0][0]) + ",...` under its header");
}

//! Rigol DS1000Z/MSO1000Z CSV: the header `X,CH1[,CH2...],Start,Increment`, then
//! `Sequence,VOLT[,VOLT...],<start s>,<increment s>`, then rows `<index>,<V>...`: the time is
//! not written, it is start + index * increment.
Layout rigol_layout(const std::vector<Fields>& head, const std::string& path) {
  const Fields& header = head[0];
  const auto start = std::find(header.begin(), header.end(), "Start");
  const auto increment = std::find(header.begin(), header.end(), "Increment");
  if (start == header.end() || increment == header.end() || start - header.begin() < 2)
    fail(path, 1, "a Rigol header is `X,CH1,Start,Increment`: the channels, then Start and Increment");
  const auto start_column = static_cast<std::size_t>(start - header.begin());
  const auto increment_column = static_cast<std::size_t>(increment - header.begin());
  if (head.size() < 2 || head[1].size() <= std::max(start_column, increment_column))
    fail(path, 2, "a Rigol export gives the start and the increment [s] in columns " + std::to_string(start_column + 1) +
                      " and " + std::to_string(increment_column + 1) + " of its second line");
  Layout layout;
  for (const std::size_t c : {start_column, increment_column}) {
    std::string why;
    const auto value = parse_number(head[1][c], &why);
    if (!value) fail(path, 2, "column " + std::to_string(c + 1) + " ('" + header[c] + "') = '" + text_excerpt(head[1][c]) + "' " + why);
    (c == start_column ? layout.start_s : layout.increment_s) = *value;
  }
  if (!(layout.increment_s > 0.0))
    fail(path, 2, "column " + std::to_string(increment_column + 1) + " ('Increment') = " + format_number(layout.increment_s) +
                      " s: the sample interval must be > 0");
  layout.names.assign(header.begin(), start);
  layout.units.assign(head[1].begin(), head[1].begin() + static_cast<std::ptrdiff_t>(start_column));
  layout.units_line = 2;
  layout.data_line = 2;
  layout.time_from_index = true;
  layout.channels = columns_after_time(layout.names.size());
  return layout;
}

//! Teledyne LeCroy "Spreadsheet" export (WaveRunner/WaveSurfer operator's manuals): a
//! preamble from `LECROY<model>,...,Waveform` and `Segments,...`, then the header
//! `Time,Ampl` above the samples, in s and in the channel's unit (V for a voltage probe).
Layout lecroy_layout(const std::vector<Fields>& head, const std::string& path) {
  Layout layout = header_row_layout(head, "Time", "", "", 1);
  if (layout.names.empty())
    fail(path, 1, "a LeCroy export has a `Time,Ampl` row after its preamble; it is not in the first " +
                      std::to_string(HEAD_LINES) + " lines");
  return layout;
}

//! PicoScope 6/7 text export (PicoScope 6 user's guide, "Text formats"): the header
//! `Time,Channel A[,Channel B...]`, a units row `(µs),(V)...`, then the samples; commas or tabs.
Layout picoscope_layout(const std::vector<Fields>& head, const std::string& path) {
  return header_and_units_layout(head, path,
                                 "a PicoScope export has a units row (`(us),(V)`) with one unit per column under its header");
}

Layout layout_of(RecordFormat format, const std::vector<Fields>& head, const std::string& path) {
  switch (format) {
    case RecordFormat::tektronix: return tektronix_layout(head, path);
    case RecordFormat::keysight: return keysight_layout(head, path);
    case RecordFormat::rigol: return rigol_layout(head, path);
    case RecordFormat::lecroy: return lecroy_layout(head, path);
    case RecordFormat::picoscope: return picoscope_layout(head, path);
    default: break;
  }
  throw InputError(path + ": no layout for format " + record_format_name(format));
}

std::string describe_column(const Layout& layout, std::size_t column) {
  return "column " + std::to_string(column + 1) + " ('" + layout.names[column] + "')";
}

//! The voltage column: the one named `--column`, or the first channel.
std::size_t voltage_column(const Layout& layout, const std::string& wanted, const std::string& path) {
  if (layout.channels.empty()) fail(path, layout.data_line, "no voltage column beside the time");
  if (wanted.empty()) return layout.channels.front();
  std::string known;
  for (const std::size_t c : layout.channels) {
    if (same_letters(layout.names[c], wanted)) return c;
    known += (known.empty() ? "" : ", ") + layout.names[c];
  }
  throw InputError(path + ": --column " + wanted + " is not a voltage column of this record (its columns: " + known + ")");
}

//! The value of the last digit `text` is printed to ("-5.0000000E-04" -> 1e-11). A zero in
//! exponent notation ("0.000000e+00") is 0 exactly: its exponent says nothing of its digits.
double printed_step(std::string_view text) {
  int exponent = 0;
  const std::size_t e = text.find_first_of("eE");
  if (e != std::string_view::npos) {
    if (text.substr(0, e).find_first_of("123456789") == std::string_view::npos) return 0.0;
    std::string_view digits = text.substr(e + 1);
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    std::from_chars(digits.data(), digits.data() + digits.size(), exponent);
  }
  const std::string_view mantissa = text.substr(0, e);
  const std::size_t point = mantissa.find_first_of(".,");
  const std::size_t decimals = point == std::string_view::npos ? 0 : mantissa.size() - point - 1;
  return std::pow(10.0, exponent - static_cast<int>(decimals));
}

//! A number in `field`; a decimal comma is read as a point when commas do not delimit.
double number_in(std::string field, char delimiter, const Layout& layout, std::size_t column, const std::string& path,
                 std::size_t line) {
  if (delimiter != ',' && field.find('.') == std::string::npos) std::replace(field.begin(), field.end(), ',', '.');
  std::string why;
  const auto value = parse_number(field, &why);
  if (!value) fail(path, line, describe_column(layout, column) + " = '" + text_excerpt(field) + "' " + why);
  return *value;
}

//! Oscilloscopes sample on a uniform clock and print its times rounded: each time must lie
//! on the grid from the first to the last within what its printing can have moved it (and
//! 1e-6 of a step, as the uniform check of the analysis); it is then replaced by the grid.
void put_on_uniform_grid(std::vector<double>& times, const std::vector<double>& printed, const std::vector<std::size_t>& lines,
                         const Layout& layout, const std::string& path) {
  const std::size_t n = times.size();
  if (n < 2) return;
  const double step = (times.back() - times.front()) / static_cast<double>(n - 1);
  if (!(step > 0.0))
    fail(path, lines.back(), describe_column(layout, layout.time_column) + ": the last time " + format_number(times.back()) +
                                 " s is not after the first " + format_number(times.front()) + " s: times must increase");
  const double ends = std::max(printed.front(), printed.back());
  for (std::size_t k = 0; k < n; ++k) {
    const double grid = times.front() + static_cast<double>(k) * step;
    const double slack = 1e-6 * step + 0.5 * (printed[k] + ends);
    if (std::abs(times[k] - grid) > slack)
      fail(path, lines[k], describe_column(layout, layout.time_column) + ": t = " + format_number(times[k]) +
                               " s is off the uniform grid of the record (from " + format_number(times.front()) +
                               " s in steps of " + format_number(step) + " s) by " + format_number(times[k] - grid) +
                               " s, more than its printed precision: the analysis needs uniformly sampled records");
    times[k] = grid;
  }
}

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

bool is_record_text(const std::string& path, const RecordReadOptions& options) {
  if (!options.hdf5.dataset.empty()) return false;
  const std::string extension = lower_extension(path);
  return options.format != RecordFormat::automatic || extension == ".csv" || extension == ".tsv" || extension == ".txt";
}

SignalInput read_record_text(const std::string& path, const RecordReadOptions& options) {
  std::ifstream in = open_input_file(path, "the signal CSV file");
  std::vector<std::string> lines;
  std::string line;
  while (lines.size() < HEAD_LINES && std::getline(in, line)) lines.push_back(line);
  if (lines.empty()) fail(path, 1, "the file is empty: expected a header `t,V` or an oscilloscope export");
  const char delimiter = delimiter_of(lines);
  std::vector<Fields> head;
  for (const std::string& l : lines) head.push_back(split(l, delimiter));

  RecordFormat format = options.format;
  if (format == RecordFormat::automatic) {
    const auto detected = detect_record_format(head);
    if (!detected)
      fail(path, 1, "header must be `t,V` (time in s, voltage in V), or an oscilloscope export stengmc recognises (--format "
                    "tektronix, keysight, rigol, lecroy or picoscope); the first line is '" + text_excerpt(trim_blanks(lines[0])) + "'");
    format = *detected;
  }
  if (format == RecordFormat::plain) {
    if (!options.column.empty() && options.column != "V")
      throw InputError(path + ": --column " + options.column + ": a plain `t,V` record has one voltage column, V");
    return read_signal_csv(path);
  }

  const Layout layout = layout_of(format, head, path);
  const std::size_t column = voltage_column(layout, options.column, path);
  const std::optional<double> time_scale =
      layout.time_from_index ? std::optional<double>(1.0) : time_unit_scale(layout.units[layout.time_column]);
  if (!time_scale)
    fail(path, layout.units_line, describe_column(layout, layout.time_column) + " is in '" +
                                      text_excerpt(layout.units[layout.time_column]) + "', not a unit of time (s, ms, us, ns, ps)");
  const std::optional<double> voltage_scale = voltage_unit_scale(layout.units[column]);
  if (!voltage_scale)
    fail(path, layout.units_line, describe_column(layout, column) + " is in '" + text_excerpt(layout.units[column]) +
                                      "', not a unit of voltage (V, mV, uV, kV)");

  SignalInput input;
  std::vector<double> printed;     // the last digit of each time as printed [s]
  std::vector<std::size_t> where;  // the line of each sample
  const auto read_sample = [&](const std::string& text, std::size_t number) {
    if (blank(text)) return;
    const Fields fields = split(text, delimiter);
    if (fields.size() <= std::max(layout.time_column, column))
      fail(path, number, std::to_string(fields.size()) + " field(s) in '" + text_excerpt(trim_blanks(text)) + "'; the time is " +
                             describe_column(layout, layout.time_column) + ", the voltage " + describe_column(layout, column));
    const double t = number_in(fields[layout.time_column], delimiter, layout, layout.time_column, path, number);
    const double v = number_in(fields[column], delimiter, layout, column, path, number) * *voltage_scale;
    if (std::abs(v) > MAX_ANALYSED_VOLTAGE_V)
      fail(path, number, describe_column(layout, column) + ": V = " + format_number(v) +
                             " is beyond what the analysis can square and sum (|V| <= 1e100 V)");
    if (layout.time_from_index) {
      input.times_s.push_back(layout.start_s + t * layout.increment_s);
      printed.push_back(0.0);  // an index is exact
    } else {
      input.times_s.push_back(t * *time_scale);
      printed.push_back(printed_step(fields[layout.time_column]) * *time_scale);
    }
    input.voltage_v.push_back(v);
    where.push_back(number);
  };
  for (std::size_t i = layout.data_line; i < lines.size(); ++i) read_sample(lines[i], i + 1);
  std::size_t number = lines.size();
  while (std::getline(in, line)) read_sample(line, ++number);
  if (input.times_s.empty()) fail(path, number, "no samples after the " + record_format_name(format) + " header");
  put_on_uniform_grid(input.times_s, printed, where, layout, path);
  return input;
}

}  // namespace stengmc
