// Reports of the tolerance analysis: text for designers, JSON, CSV, and two SVG pictures
// (the variation band with the Monte Carlo envelope; a contact-zone detail like the paper's
// Figure 5). Doubles here are for display only.
#include "core/plot_axis.hpp"

#include <hipair/error.hpp>
#include <hipair/tolerance.hpp>
#include <hipair/tolerance_scale.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

namespace hipair {
namespace {

constexpr double pi = std::numbers::pi;

std::string number(double value, int digits = 6) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

// Display unit of the follower: degrees for rotations (with the factor), mm for translations.
double unit_factor(bool rotates) { return rotates ? 180 / pi : 1.0; }
const char* unit_name(bool rotates) { return rotates ? "deg" : "mm"; }
const char* driver_unit(bool rotates) { return rotates ? "deg" : "mm"; }

// The unit a translating part's coordinates are held in: "mm", or "1e400 mm" for a result in
// units of 10^400 mm (ToleranceResult::length_exponent: a mechanism analysed on its rescaled copy).
std::string length_unit(const ToleranceResult& r) {
  return r.length_exponent == 0 ? std::string("mm") : "1e" + std::to_string(r.length_exponent) + " mm";
}
// The picture's axis unit of a part: "deg", "mm" or "1e400 mm" (its numbers as held; "mm" for a
// picture at the file's scale, session 68).
std::string axis_unit(const ToleranceResult& r, bool rotates, bool file = false) {
  return rotates ? "deg" : file ? std::string("mm") : length_unit(r);
}

// A number of the result shown as number(value * factor, digits) for a rotating part (deg, or a
// ratio), and for a translating one (a length held in units of 10^E mm) in mm: the decimal
// number() prints with its exponent moved by E ("0.5" -> "0.5e400", "1.2e-05" -> "1.2e395"),
// exactly. E = 0: number(value, digits).
// A decimal text of number() with its exponent moved by `by` ("0.5" -> "0.5e400"): the value
// times 10^by, exactly as printed. Unchanged for by = 0, 0, inf and nan.
std::string moved(std::string text, long by) {
  if (by == 0 || text.find_first_of("ni") != std::string::npos ||
      text.substr(0, text.find('e')).find_first_of("123456789") == std::string::npos)   // 0, -0, 0.00 (a tick)
    return text;
  long exponent = 0;
  std::size_t e = text.find('e');
  if (e != std::string::npos) {
    exponent = std::stol(text.substr(e + 1));
    text.erase(e);
  }
  return text + "e" + std::to_string(exponent + by);
}

std::string shown(const ToleranceResult& r, double value, bool rotates, int digits) {
  if (rotates) return number(value * unit_factor(true), digits);
  std::string text = number(value, digits);
  if (r.length_exponent == 0 || !std::isfinite(value) || value == 0) return text;
  return moved(text, r.length_exponent);
}

// Session 67 (scale67): a model whose parameters lie beyond the doubles is analysed with each
// parameter in units of 10^k_i its file's (k_i = E times its length dimension;
// analyze_tolerances(..., parameter_exponents)): `k` those exponents (empty: all 0). The text report shows the
// parameters' numbers at the file's scale; so do tolerance.json and sensitivity.csv (scalejson67:
// json_at, json_exact_at below).
long exponent_of(const std::vector<long>& k, std::size_t i) { return i < k.size() ? k[i] : 0; }
long exponent_of(const ToleranceResult& r, const std::vector<long>& k, const std::string& name) {
  for (std::size_t i = 0; i < r.parameters.size(); ++i)
    if (r.parameters[i].name == name) return exponent_of(k, i);
  return 0;
}
// The unit of parameter i's numbers in the analysis: "1e400 mm", "1e800 mm^2"; "" as written.
std::string parameter_unit(const ToleranceResult& r, const std::vector<long>& k, std::size_t i) {
  const long e = exponent_of(k, i);
  if (e == 0 || r.length_exponent == 0) return "";
  const long d = e / r.length_exponent;
  return "1e" + std::to_string(e) + " mm" + (d == 1 ? std::string() : "^" + std::to_string(d));
}
// A sensitivity per unit of a parameter in units of 10^k its file's, at the file's scale: its
// decimal's exponent moved by -k (and by E for a translating follower, as shown()).
std::string sensitivity_text(const ToleranceResult& r, double value, long k) {
  if (k == 0) return shown(r, value, r.follower_rotates, 4);
  const long by = (r.follower_rotates ? 0 : r.length_exponent) - k;
  std::string text = moved(number(value * unit_factor(r.follower_rotates), 4), by);
  if (text.size() > 2 && text.compare(text.size() - 2, 2, "e0") == 0) text.erase(text.size() - 2);
  return text;
}

// An exact parameter value of the analysis at the file's scale: "(v)e400", exact.
std::string file_scale_value(const Rational& value, long k) {
  if (k == 0 || sgn(value) == 0) return to_exact_string(value);
  return "(" + to_exact_string(value) + ")e" + std::to_string(k);
}

// Session 67 (scalejson67): tolerance.json and sensitivity.csv of a model whose parameters were
// rescaled by their length dimensions (some k_i not 0) are written at the file's scale: a number
// held in units of 10^by is written as a string, the decimal of the double (JSON: its shortest
// round-trip digits; CSV: `digits` significant digits) with its exponent moved by `by` — the
// decimal times 10^by, exactly ("0.5" -> "0.5e400") — and an exact value (a parameter's nominal
// and range ends, worst and witness values) exactly: its terminating decimal with the exponent
// ("4.48e400"), else "(p/q)e400" (file_scale_value, as report.txt). by = 0: as before.
bool at_files_scale(const std::vector<long>& k) {
  return std::any_of(k.begin(), k.end(), [](long e) { return e != 0; });
}
std::string shortest(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : number(value, 17);
}
nlohmann::ordered_json json_at(double value, long by) {
  if (by == 0 || !std::isfinite(value)) return value;
  return moved(shortest(value), by);
}
// An exact value times 10^by as a string: its decimal when it terminates ("4.48e400", "-2e-300"),
// else "(p/q)e400" (report.txt's form).
std::string exact_decimal_at(const Rational& value, long by) {
  Rational v = value;
  v.canonicalize();
  mpz_class den = v.get_den();
  const unsigned long twos = mpz_remove(den.get_mpz_t(), den.get_mpz_t(), mpz_class(2).get_mpz_t());
  const unsigned long fives = mpz_remove(den.get_mpz_t(), den.get_mpz_t(), mpz_class(5).get_mpz_t());
  if (den != 1) return file_scale_value(v, by);
  if (sgn(v) == 0) return "0";
  const unsigned long places = std::max(twos, fives);
  mpz_class scaled;
  mpz_ui_pow_ui(scaled.get_mpz_t(), 10, places);
  scaled = scaled * v.get_num() / v.get_den();   // exact: the denominator divides 10^places
  std::string digits = mpz_class(abs(scaled)).get_str();
  if (places > 0) {
    if (digits.size() <= places) digits.insert(0, places + 1 - digits.size(), '0');
    digits.insert(digits.size() - places, ".");
    while (digits.back() == '0') digits.pop_back();
    if (digits.back() == '.') digits.pop_back();
  }
  return (sgn(v) < 0 ? "-" : "") + digits + (by == 0 ? std::string() : "e" + std::to_string(by));
}
nlohmann::ordered_json json_exact_at(const Rational& value, long by) {
  return by == 0 ? value.get_str() : exact_decimal_at(value, by);
}

// A CSV column holding a translating part's coordinates: `name`, or "name_1e400mm" when they are
// in units of 10^400 mm.
std::string column(const ToleranceResult& r, const std::string& name, bool rotates) {
  return rotates || r.length_exponent == 0 ? name : name + "_1e" + std::to_string(r.length_exponent) + "mm";
}

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string distribution_text(const ToleranceResult& r, std::size_t i) {
  const Parameter& p = r.parameters[i];
  if (p.range.lo == p.range.hi) return "fixed";
  switch (p.distribution) {
    case Parameter::Distribution::uniform: return "uniform";
    case Parameter::Distribution::normal: return "normal (sigma given), truncated";
    case Parameter::Distribution::none: return "normal (sigma = width/6), truncated";
  }
  return "";
}

// A simple plot frame mapping data to a 900 x 420 picture, with nice ticks (core/plot_axis).
struct Frame {
  PlotAxis x, y;
  double left = 80, right = 880, top = 40, bottom = 380;
  double px(long double v) const { return left + x.fraction(v) * (right - left); }
  double py(long double v) const { return bottom - y.fraction(v) * (bottom - top); }
};

// The frame for x data from x_first to x_last and y data in [y_lo, y_hi], `pad` of the y span
// added on each side.
Frame frame_of(double x_first, double x_last, double y_lo, double y_hi, double pad) {
  PlotAxisOptions x_options;
  x_options.max_ticks = 9;
  PlotAxisOptions y_options;
  y_options.pad = pad;
  return Frame{plot_axis(x_first, x_last, x_options), plot_axis(y_lo, y_hi, y_options)};
}

std::string polyline(const Frame& f, const std::vector<double>& x, const std::vector<double>& y, const std::string& style) {
  std::string out;
  std::string points;
  auto flush = [&] {
    if (!points.empty()) out += "<polyline fill=\"none\" " + style + " points=\"" + points + "\"/>\n";
    points.clear();
  };
  // (no samples: x is the placeholder {0, 1} and y is empty)
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (std::isnan(y[i])) {
      flush();
      continue;
    }
    points += number(f.px(x[i]), 7) + "," + number(f.py(y[i]), 7) + " ";
  }
  flush();
  return out;
}

std::string axes(const Frame& f, const std::string& title, const std::string& x_label, const std::string& y_label) {
  std::ostringstream out;
  out << "<rect x=\"0\" y=\"0\" width=\"960\" height=\"460\" fill=\"white\"/>\n";
  out << "<text x=\"480\" y=\"22\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"15\">"
      << xml_escape(title) << "</text>\n";
  out << "<rect x=\"" << f.left << "\" y=\"" << f.top << "\" width=\"" << f.right - f.left << "\" height=\""
      << f.bottom - f.top << "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (std::size_t k = 0; k < f.x.ticks.size(); ++k)
    out << "<text x=\"" << f.px(f.x.ticks[k]) << "\" y=\"" << f.bottom + 16
        << "\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"11\">" << f.x.labels[k] << "</text>\n";
  if (!f.x.base_label.empty())
    out << "<text x=\"" << f.left << "\" y=\"" << f.bottom + 30
        << "\" text-anchor=\"start\" font-family=\"sans-serif\" font-size=\"11\">" << f.x.base_label << "</text>\n";
  for (std::size_t k = 0; k < f.y.ticks.size(); ++k) {
    double y = f.py(f.y.ticks[k]);
    out << "<text x=\"" << f.left - 6 << "\" y=\"" << y + 4
        << "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"11\">" << f.y.labels[k] << "</text>\n";
    out << "<line x1=\"" << f.left << "\" x2=\"" << f.right << "\" y1=\"" << y << "\" y2=\"" << y
        << "\" stroke=\"#eee\"/>\n";
  }
  if (!f.y.base_label.empty())
    out << "<text x=\"" << f.left - 6 << "\" y=\"" << f.top - 6
        << "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"11\">" << f.y.base_label << "</text>\n";
  out << "<text x=\"480\" y=\"412\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"12\">"
      << xml_escape(x_label) << "</text>\n";
  out << "<text x=\"16\" y=\"210\" transform=\"rotate(-90 16 210)\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"12\">"
      << xml_escape(y_label) << "</text>\n";
  return out.str();
}

std::string legend(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::ostringstream out;
  double x = 90;
  for (const auto& [style, text] : entries) {
    out << "<line x1=\"" << x << "\" x2=\"" << x + 24 << "\" y1=\"440\" y2=\"440\" " << style << "/>\n";
    out << "<text x=\"" << x + 30 << "\" y=\"444\" font-family=\"sans-serif\" font-size=\"11\">" << xml_escape(text)
        << "</text>\n";
    x += 40 + 6.5 * static_cast<double>(text.size());
  }
  return out.str();
}

// The bracket's certified lower end: the scale of a valid no-jam certificate (its named sides
// apart and a free follower path proved: the verifier's verdict "valid") from the same run, hence
// over the same driver range and the same varied parameters, below the exact jam witness. The
// threshold then lies between the two, each end proved: no jam at or below it (the certificate,
// checked by hipair-verify), a jam at the upper end (the exact witness and its C-space).
std::optional<Rational> certified_lower_end(const ToleranceResult& r) {
  if (!r.threshold || !r.threshold->bracketed || !r.threshold->bracket_confirmed || !r.certification) return std::nullopt;
  const ToleranceCertification& c = *r.certification;
  if (c.outcome != ToleranceCertification::Outcome::certified || c.unproven || !c.certificate) return std::nullopt;
  if (!(c.scale < r.threshold->bracket_above))
    throw NumericError("a valid no-jam certificate at scale " + to_exact_string(c.scale) +
                       " is not below the exact jam witness at scale " + to_exact_string(r.threshold->bracket_above) +
                       ": the two proofs contradict each other");
  return c.scale;
}

}  // namespace

namespace {
std::string text_report(const ToleranceResult& r, const std::vector<long>& k);
std::string json_report(const ToleranceResult& r, const std::vector<long>& k);
std::string sensitivity_csv(const ToleranceResult& r, const std::vector<long>& k);
}  // namespace

std::string tolerance_text_report(const ToleranceResult& r) { return text_report(r, {}); }
std::string tolerance_text_report(const ToleranceResult& r, const std::vector<long>& k) { return text_report(r, k); }
std::string tolerance_json_report(const ToleranceResult& r) { return json_report(r, {}); }
std::string tolerance_json_report(const ToleranceResult& r, const std::vector<long>& k) { return json_report(r, k); }
std::string tolerance_sensitivity_csv(const ToleranceResult& r) { return sensitivity_csv(r, {}); }
std::string tolerance_sensitivity_csv(const ToleranceResult& r, const std::vector<long>& k) { return sensitivity_csv(r, k); }

namespace {
std::string text_report(const ToleranceResult& r, const std::vector<long>& exponents) {
  std::ostringstream out;
  const char* u = unit_name(r.follower_rotates);
  // follower values and driver positions, in deg or mm (a length held in 10^E mm shown in mm)
  auto fv = [&](double v, int digits) { return shown(r, v, r.follower_rotates, digits); };
  auto dv = [&](double v, int digits) { return shown(r, v, r.driver_rotates, digits); };
  out << "Tolerance analysis of '" << r.model_name << "': " << r.driver << " drives " << r.follower << "\n";
  if (!r.chain.empty()) {
    out << "Assembly chain of " << r.chain.size() << " pairs: " << r.driver;
    for (const ChainStage& stage : r.chain) out << " -> " << stage.follower;
    out << " (the pairs' kinematic functions and sensitivities composed; regions name each pair's contact)\n";
  }
  std::size_t toleranced = 0;
  for (const Parameter& p : r.parameters) toleranced += p.range.lo != p.range.hi;
  out << toleranced << " toleranced parameters of " << r.parameters.size() << "; follower positions in " << u
      << ", driver in " << driver_unit(r.driver_rotates) << ".\n";
  {
    std::string rescaled;
    for (std::size_t i = 0; i < r.parameters.size(); ++i)
      if (exponent_of(exponents, i) != 0) rescaled += (rescaled.empty() ? "" : ", ") + r.parameters[i].name + " (" + parameter_unit(r, exponents, i) + ")";
    if (!rescaled.empty())
      out << "Parameters beyond the doubles, analysed in the units named (sensitivities and values shown here at the "
             "model's scale): "
          << rescaled << ".\n";
  }
  out << "\n";
  std::size_t contact = 0;
  double widest_linear = 0, widest_rss = 0, widest_certified = 0, at = 0;
  for (const VariationSample& s : r.samples) {
    if (!s.contact) continue;
    ++contact;
    if (s.linear_upper - s.linear_lower > widest_linear) {
      widest_linear = s.linear_upper - s.linear_lower;
      at = s.driver;
    }
    widest_rss = std::max(widest_rss, s.rss_upper - s.rss_lower);
    widest_certified = std::max(widest_certified, s.certified.upper - s.certified.lower);
  }
  out << "Variation of the follower along the path (" << r.samples.size() << " driver positions, " << contact
      << " in contact):\n";
  out << "  worst case, linearised: +-" << fv(0.5 * widest_linear, 4) << " " << u << " at most (driver "
      << dv(at, 5) << ")\n";
  out << "  worst case, certified:  +-" << fv(0.5 * widest_certified, 4) << " " << u
      << " at most (interval arithmetic over the whole tolerance box, " << r.certified_boxes
      << " sub-boxes; at most " << fv(r.certified_excess, 3) << " " << u << " wider than linearised)\n";
  out << "  statistical (mean +- 3 sigma): +-" << fv(0.5 * widest_rss, 4) << " " << u << " at most\n\n";
  out << "Contact regions and their dominant parameters (the paper's Table 1):\n";
  for (const ContactRegion& region : r.regions) {
    out << "  " << region.contact << "  (driver " << dv(region.driver_start, 5) << " .. "
        << dv(region.driver_end, 5) << "; +-" << fv(region.linear_half_width, 3) << " " << u << ")\n";
    for (std::size_t k = 0; k < region.ranked.size() && k < 5; ++k) {
      const ParameterContribution& c = region.ranked[k];
      if (c.contribution <= 0) break;
      out << "      " << c.parameter << ": " << number(100 * c.share, 3) << " %  ("
          << sensitivity_text(r, c.sensitivity, exponent_of(r, exponents, c.parameter)) << " " << u << " per unit)\n";
    }
  }
  if (r.monte_carlo) {
    const MonteCarloSummary& mc = *r.monte_carlo;
    out << "\nMonte Carlo: " << mc.samples << " parameter vectors (seed " << mc.seed << "), " << mc.evaluations
        << " certified follower positions in " << number(mc.seconds, 3) << " s\n";
    out << "  outside the certified band: " << mc.outside_certified << (mc.outside_certified == 0 ? " (as it must be)" : " (A DEFECT)") << "\n";
    out << "  not certified: " << mc.not_certified
        << (mc.not_certified == 0 ? "" : " (positions where no value could be certified, even by the wider search: the Monte "
                                          "Carlo's own failures, neither inside nor outside the band; not among the "
                                          "certified positions)")
        << "\n";
    if (mc.undecided_certified > 0)
      out << "  undecided against the certified band: " << mc.undecided_certified
          << " (certified values whose enclosure meets the band's edge: neither inside nor outside it)\n";
    out << "  outside the linearised band: " << mc.outside_linear << " (linearisation error up to "
        << fv(mc.linearisation_error, 3) << " " << u << ")\n";
  }
  if (r.threshold) {
    const JammingThreshold& t = *r.threshold;
    out << "\nJamming threshold:\n";
    if (!t.found) {
      out << "  not found (no bounded channel along the path)\n";
    } else {
      out << "  the channel can close when every tolerance is scaled by " << number(t.scale, 4)
          << " (linearised), at driver " << dv(t.driver, 5) << " " << driver_unit(r.driver_rotates)
          << ", between '" << t.lower_contact << "' and '" << t.upper_contact << "' (nominal play "
          << fv(t.nominal_play, 4) << " " << u << ")\n";
      if (t.certified_open_scale > 0)
        out << "  certified open there up to scale " << number(t.certified_open_scale, 4) << "\n";
      out << "  exact check: " << (t.confirmed ? "CONFIRMED — " : "not confirmed — ") << t.evidence << "\n";
      if (t.bracketed) {
        out << "  bracket (corner search, " << t.bracket_steps << " steps): no jam found at scale "
            << to_exact_string(t.bracket_below) << ", exact jam witness at scale " << to_exact_string(t.bracket_above)
            << " (driver " << dv(t.bracket_driver.get_d(), 9) << " " << driver_unit(r.driver_rotates) << ")\n";
        // (a large pair's check is on exact kernel slices, no C-space: its evidence says so)
        const bool kernels = t.bracket_evidence.rfind("exact slice", 0) == 0;
        out << (kernels ? "  exact check at the witness: " : "  exact C-space at the witness: ")
            << (t.bracket_confirmed ? "CONFIRMED — " : "not confirmed — ") << t.bracket_evidence << "\n";
        if (auto lower = certified_lower_end(r))
          out << "  certified bracket: the threshold lies in [" << to_exact_string(*lower) << ", "
              << to_exact_string(t.bracket_above) << "] (lower end " << number(Rational(*lower / t.bracket_above).get_d(), 3)
              << " of the upper): no jam up to " << to_exact_string(*lower)
              << " (the tolerance certificate below, verdict valid), a jam at " << to_exact_string(t.bracket_above)
              << " (the exact witness)\n";
        else
          out << "  certified bracket: only the upper end is proved (a valid no-jam certificate below it would prove "
                 "the lower end: --certify --certify-free-path with --certify-scale below the bracket)\n";
      } else if (!t.bracket_evidence.empty()) {
        out << "  bracket: " << t.bracket_evidence << "\n";
      }
    }
  }
  if (r.contact_changes) {
    const ContactChangeCheck& c = *r.contact_changes;
    out << "\nContacts appearing or disappearing under tolerance (" << c.positions << " driver positions, "
        << c.candidates << " curves beyond a side of the channel: " << c.excluded << " certainly never reach it there, "
        << c.possible << " might, " << c.undecided << " not enclosed; " << c.switch_shifts
        << " of those that might are contact switches moving along the path):\n";
    if (c.changes.empty()) out << "  none found\n";
    for (const ContactChange& change : c.changes) {
      bool appears = change.kind == ContactChange::Kind::appears;
      out << "  " << (appears ? "APPEARS: '" : "DISAPPEARS: '") << change.contact << "' "
          << (appears ? "overtakes '" : "is overtaken by '") << change.other << "' on the channel's "
          << (change.lower_side ? "lower" : "upper") << " side, driver " << dv(change.driver_first, 5) << " .. "
          << dv(change.driver_last, 5) << " " << driver_unit(r.driver_rotates) << " (" << change.positions
          << " positions); at driver " << dv(change.driver, 5) << " by " << fv(change.overshoot, 4) << " " << u
          << " (linearised" << (change.certified_at_witness ? "; reversed order certified at the witness" : "") << ")\n";
      out << "    witness:";
      for (const auto& [name, value] : change.witness)
        out << " " << name << "=" << file_scale_value(value, exponent_of(r, exponents, name));
      // (an exact slice at every position showing the channel bounded by other contacts: refuted)
      const bool refuted = change.evidence.rfind("refuted: ", 0) == 0;
      out << "\n    exact check: " << (change.confirmed ? "CONFIRMED — " : refuted ? "REFUTED — " : "not confirmed — ")
          << (refuted ? change.evidence.substr(9) : change.evidence) << "\n";
    }
  }
  if (r.certification) {
    const ToleranceCertification& c = *r.certification;
    out << "\nTolerance certificate (no jam, tolerances x " << to_exact_string(c.scale) << "):\n";
    switch (c.outcome) {
      case ToleranceCertification::Outcome::certified:
        if (c.unproven)
          out << "  WRITTEN, NOT PROVED: " << c.leaves << " leaves (" << c.attempts << " boxes tried) in "
              << number(c.seconds_produce, 3) << " s; the verifier's code (" << number(c.seconds_verify, 3)
              << " s) checked that the named contact sides stay apart over every leaf, but did not prove a free "
                 "follower path across the range (check 7: "
              << c.reason << "): verdict unproven, the claim 'no jam' is not proved (docs/certify.md)"
              // a leaf accepted without a witness path: the producer's witness-split budget ran out (session 71)
              << (c.reason.find(" has no witness path for the follower") != std::string::npos
                      ? "; such a leaf is split at most --certify-witness-splits times along a branch: a larger "
                        "budget may give it a witness path"
                      : "")
              << "\n";
        else
          out << "  CERTIFIED: " << c.leaves << " leaves (" << c.attempts << " boxes tried) in "
              << number(c.seconds_produce, 3) << " s, re-checked by the verifier's code in " << number(c.seconds_verify, 3)
              << " s (the named sides apart over every leaf, and a free follower path across the range: no jam)\n";
        break;
      case ToleranceCertification::Outcome::jams:
        out << "  JAMS: " << c.reason << "\n";
        break;
      case ToleranceCertification::Outcome::undecided:
        out << "  undecided (no certificate): " << c.reason << "\n";
        break;
      case ToleranceCertification::Outcome::interferes:
        out << "  INTERFERES: " << c.reason << "\n";
        break;
    }
  }
  for (const std::string& note : r.notes) out << "\nNote: " << note << "\n";
  return out.str();
}

}  // namespace

namespace {
std::string json_report(const ToleranceResult& r, const std::vector<long>& k) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["model"] = r.model_name;
  j["driver"] = r.driver;
  j["follower"] = r.follower;
  // parameters rescaled by their dimensions (session 67): every number at the file's scale, a
  // translating follower's (driver's) lengths moved by E = ef (ed), parameter i's by k_i
  const bool file = at_files_scale(k);
  const long ef = file && !r.follower_rotates ? r.length_exponent : 0;
  const long ed = file && !r.driver_rotates ? r.length_exponent : 0;
  j["follower_unit"] = r.follower_rotates ? "rad" : file ? std::string("mm") : length_unit(r);
  // a result in units of 10^E mm: every length of the report (a translating part's coordinates)
  if (r.length_exponent != 0 && !file) j["length_unit"] = length_unit(r);
  if (!r.chain.empty()) {
    ordered_json chain = ordered_json::array();
    for (const ChainStage& stage : r.chain)
      chain.push_back({{"driver", stage.driver},
                       {"follower", stage.follower},
                       {"contact_positions", stage.contact_positions},
                       {"certified_boxes", stage.certified_boxes}});
    j["chain"] = chain;
  }
  ordered_json parameters = ordered_json::array();
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const Parameter& p = r.parameters[i];
    const long e = exponent_of(k, i);
    parameters.push_back({{"name", p.name},
                          {"nominal", e == 0 ? ordered_json(p.nominal.get_d()) : ordered_json(exact_decimal_at(p.nominal, e))},
                          {"lower", e == 0 ? ordered_json(p.range.lo.get_d()) : ordered_json(exact_decimal_at(p.range.lo, e))},
                          {"upper", e == 0 ? ordered_json(p.range.hi.get_d()) : ordered_json(exact_decimal_at(p.range.hi, e))},
                          {"distribution", distribution_text(r, i)},
                          {"sigma", json_at(r.sigma[i], e)},
                          {"mean_deviation", json_at(r.mean_shift[i], e)}});
  }
  j["parameters"] = parameters;
  ordered_json regions = ordered_json::array();
  for (const ContactRegion& region : r.regions) {
    ordered_json ranked = ordered_json::array();
    for (const ParameterContribution& c : region.ranked)
      if (c.contribution > 0) {
        ranked.push_back({{"parameter", c.parameter},
                          {"sensitivity", json_at(c.sensitivity, ef - exponent_of(r, k, c.parameter))},
                          {"contribution", json_at(c.contribution, ef)},
                          {"share", c.share}});
      }
    regions.push_back({{"contact", region.contact},
                       {"driver_start", json_at(region.driver_start, ed)},
                       {"driver_end", json_at(region.driver_end, ed)},
                       {"linear_half_width", json_at(region.linear_half_width, ef)},
                       {"ranked", ranked}});
  }
  j["regions"] = regions;
  j["certified"] = {{"boxes", r.certified_boxes}, {"largest_excess_over_linearised", json_at(r.certified_excess, ef)}};
  if (r.monte_carlo) {
    const MonteCarloSummary& mc = *r.monte_carlo;
    j["monte_carlo"] = {{"samples", mc.samples},
                        {"seed", mc.seed},
                        {"evaluations", mc.evaluations},
                        {"outside_certified", mc.outside_certified},
                        {"not_certified", mc.not_certified},
                        {"undecided_certified", mc.undecided_certified},
                        {"outside_linear", mc.outside_linear},
                        {"linearisation_error", json_at(mc.linearisation_error, ef)},
                        {"seconds", mc.seconds},
                        {"cpu_seconds", mc.cpu_seconds}};
  }
  if (r.threshold) {
    const JammingThreshold& t = *r.threshold;
    ordered_json worst = ordered_json::object();
    for (const auto& [name, value] : t.worst_values) worst[name] = json_exact_at(value, exponent_of(r, k, name));
    j["threshold"] = {{"found", t.found},
                      {"scale", t.scale},
                      {"driver", json_at(t.driver, ed)},
                      {"lower_contact", t.lower_contact},
                      {"upper_contact", t.upper_contact},
                      {"nominal_play", json_at(t.nominal_play, ef)},
                      {"certified_open_scale", t.certified_open_scale},
                      {"confirmed", t.confirmed},
                      {"confirmed_scale", t.confirmed_scale},
                      {"worst_values", worst},
                      {"evidence", t.evidence}};
    if (t.bracketed || !t.bracket_evidence.empty()) {
      ordered_json values = ordered_json::object();
      for (const auto& [name, value] : t.bracket_values) values[name] = json_exact_at(value, exponent_of(r, k, name));
      auto interval = [&](const RationalInterval& x) { return ordered_json::array({json_exact_at(x.lo, ef), json_exact_at(x.hi, ef)}); };
      j["threshold"]["bracket"] = {{"found", t.bracketed},
                                   {"steps", t.bracket_steps},
                                   {"below", t.bracket_below.get_str()},
                                   {"above", t.bracket_above.get_str()},
                                   {"relative_width", t.bracketed ? Rational((t.bracket_above - t.bracket_below) / t.bracket_above).get_d() : 0.0},
                                   {"play_below", json_at(t.bracket_play_below, ef)},
                                   {"driver", json_exact_at(t.bracket_driver, ed)},
                                   {"witness_values", values},
                                   {"witness_lower", interval(t.bracket_lower)},
                                   {"witness_upper", interval(t.bracket_upper)},
                                   {"confirmed", t.bracket_confirmed},
                                   {"evidence", t.bracket_evidence}};
      auto lower = certified_lower_end(r);
      j["threshold"]["bracket"]["certified_lower"] = lower ? ordered_json(lower->get_str()) : ordered_json(nullptr);
    }
  }
  if (r.certification) {
    const ToleranceCertification& c = *r.certification;
    const char* outcome = c.outcome == ToleranceCertification::Outcome::certified ? "certified"
                          : c.outcome == ToleranceCertification::Outcome::jams ? "jams"
                          : c.outcome == ToleranceCertification::Outcome::interferes ? "interferes" : "undecided";
    j["certificate"] = {{"outcome", outcome},
                        {"verifier_verdict", c.outcome != ToleranceCertification::Outcome::certified ? "none"
                                             : c.unproven ? "unproven" : "valid"},
                        {"scale", to_exact_string(c.scale)},
                        {"leaves", c.leaves},
                        {"boxes_tried", c.attempts},
                        {"reason", c.reason},
                        {"seconds_produce", c.seconds_produce},
                        {"seconds_verify", c.seconds_verify}};
  }
  if (r.contact_changes) {
    const ContactChangeCheck& c = *r.contact_changes;
    ordered_json changes = ordered_json::array();
    for (const ContactChange& change : c.changes) {
      ordered_json witness = ordered_json::object();
      for (const auto& [name, value] : change.witness) witness[name] = json_exact_at(value, exponent_of(r, k, name));
      changes.push_back({{"kind", change.kind == ContactChange::Kind::appears ? "appears" : "disappears"},
                         {"contact", change.contact},
                         {"other", change.other},
                         {"side", change.lower_side ? "lower" : "upper"},
                         {"driver_first", json_at(change.driver_first, ed)},
                         {"driver_last", json_at(change.driver_last, ed)},
                         {"positions", change.positions},
                         {"driver", json_at(change.driver, ed)},
                         {"overshoot", json_at(change.overshoot, ef)},
                         {"certified_at_witness", change.certified_at_witness},
                         {"witness", witness},
                         {"confirmed", change.confirmed},
                         {"confirmed_positions", change.confirmed_positions},
                         {"evidence", change.evidence}});
    }
    j["contact_changes"] = {{"positions", c.positions},
                            {"candidates", c.candidates},
                            {"excluded", c.excluded},
                            {"possible", c.possible},
                            {"undecided", c.undecided},
                            {"switch_shifts", c.switch_shifts},
                            {"changes", changes},
                            {"seconds", c.seconds}};
  }
  j["zones"] = r.zones.size();
  j["seconds"] = {{"sensitivity", r.seconds_sensitivity},
                  {"certified", r.seconds_certified},
                  {"zones", r.seconds_zones},
                  {"threshold", r.seconds_threshold}};
  j["cpu_seconds"] = {{"certified", r.cpu_seconds_certified}, {"zones", r.cpu_seconds_zones}};
  // the budgets and options that bound the result (session 72), each key with one JSON type
  // whatever its value: the accuracies numbers (1.0 stays 1.0), certify_free_path a boolean,
  // every other key a count (an integer)
  ordered_json budgets = ordered_json::object();
  for (const auto& [name, value] : r.budgets) {
    if (name.ends_with("_accuracy"))
      budgets[name] = value;
    else if (name == "certify_free_path")
      budgets[name] = value != 0.0;
    else
      budgets[name] = static_cast<long long>(value);
  }
  if (!r.chain.empty()) budgets["chain_budget_exhausted_positions"] = r.chain_budget_exhausted;
  j["budgets"] = budgets;
  j["notes"] = r.notes;
  return j.dump(1) + "\n";
}

}  // namespace

namespace {
std::string variation_csv(const ToleranceResult& r, const std::vector<long>& exponents) {
  std::ostringstream out;
  // parameters rescaled by their dimensions (session 68): a translating driver's and follower's
  // coordinates at the file's scale, each decimal's exponent moved by E exactly (as
  // sensitivity.csv), columns named as at 1 mm
  const bool file = at_files_scale(exponents);
  const long ef = file && !r.follower_rotates ? r.length_exponent : 0;
  const long ed = file && !r.driver_rotates ? r.length_exponent : 0;
  auto col = [&](const char* name, bool rotates) { return file ? std::string(name) : column(r, name, rotates); };
  out << col("driver", r.driver_rotates) << ",contact";
  for (const char* name : {"nominal", "linear_lower", "linear_upper", "rss_lower", "rss_upper", "certified_lower",
                           "certified_upper", "monte_carlo_min", "monte_carlo_max", "play"})
    out << "," << col(name, r.follower_rotates);
  out << "\n";
  auto f = [&](double v) { return moved(number(v, 12), ef); };
  for (const VariationSample& s : r.samples) {
    out << moved(number(s.driver, 12), ed) << ","
        << (s.contact ? (s.region < r.regions.size() ? "\"" + r.regions[s.region].contact + "\"" : "1") : "") << ","
        << f(s.nominal) << "," << f(s.linear_lower) << "," << f(s.linear_upper) << "," << f(s.rss_lower) << ","
        << f(s.rss_upper) << "," << f(s.certified.lower) << "," << f(s.certified.upper) << ","
        << (s.has_monte_carlo ? f(s.monte_carlo_min) : "") << "," << (s.has_monte_carlo ? f(s.monte_carlo_max) : "")
        << "," << f(s.play) << "\n";
  }
  return out.str();
}
}  // namespace

std::string tolerance_csv(const ToleranceResult& r) { return variation_csv(r, {}); }
std::string tolerance_csv(const ToleranceResult& r, const std::vector<long>& k) { return variation_csv(r, k); }

namespace {
std::string sensitivity_csv(const ToleranceResult& r, const std::vector<long>& exponents) {
  std::ostringstream out;
  // parameters rescaled by their dimensions (session 67): every number at the file's scale (see
  // json_at), columns named as at 1 mm
  const bool file = at_files_scale(exponents);
  const long ef = file && !r.follower_rotates ? r.length_exponent : 0;
  const long ed = file && !r.driver_rotates ? r.length_exponent : 0;
  auto col = [&](const char* name, bool rotates) { return file ? std::string(name) : column(r, name, rotates); };
  auto at = [](double value, long by) { return std::isfinite(value) ? moved(number(value, 10), by) : number(value, 10); };
  out << "region,contact," << col("driver_start", r.driver_rotates) << "," << col("driver_end", r.driver_rotates)
      << ",rank,parameter," << col("sensitivity", r.follower_rotates) << "," << col("contribution", r.follower_rotates)
      << ",share\n";
  for (std::size_t k = 0; k < r.regions.size(); ++k) {
    const ContactRegion& region = r.regions[k];
    for (std::size_t i = 0; i < region.ranked.size(); ++i) {
      const ParameterContribution& c = region.ranked[i];
      out << k << ",\"" << region.contact << "\"," << at(region.driver_start, ed) << "," << at(region.driver_end, ed)
          << "," << i + 1 << "," << c.parameter << "," << at(c.sensitivity, ef - exponent_of(r, exponents, c.parameter))
          << "," << at(c.contribution, ef) << "," << number(c.share, 6) << "\n";
    }
  }
  return out.str();
}
}  // namespace

namespace {
// A picture's axis of a translating part at the file's scale (session 68; by = E, else 0): its
// tick labels and base label, decimals held in units of 10^E mm, with their exponents moved by E
// ("0.5" -> "0.5e400", "+5e-07" -> "+5e393", "79 +" -> "79e400 +"), the unit "mm".
void moved_axis(PlotAxis& axis, long by) {
  if (by == 0) return;
  for (std::string& label : axis.labels) label = moved(label, by);
  if (axis.base_label.empty()) return;
  const std::string plus = " +";
  std::string& base = axis.base_label;
  const bool with_plus = base.size() > plus.size() && base.compare(base.size() - plus.size(), plus.size(), plus) == 0;
  if (with_plus) base.erase(base.size() - plus.size());
  base = moved(base, by) + (with_plus ? plus : std::string());
}

std::string band_svg(const ToleranceResult& r, const std::vector<long>& exponents) {
  const bool file = at_files_scale(exponents);
  double uf = unit_factor(r.follower_rotates), ud = unit_factor(r.driver_rotates);
  std::vector<double> x, linear_lo, linear_hi, cert_lo, cert_hi, rss_lo, rss_hi, mc_lo, mc_hi;
  double lo = 0, hi = 0;
  std::size_t held = 0, unbounded = 0;   // positions in contact; of them, without a certified band
  for (const VariationSample& s : r.samples) {
    x.push_back(s.driver * ud);
    double nan = std::numeric_limits<double>::quiet_NaN();
    auto d = [&](double v) { return s.contact ? (v - s.nominal) * uf : nan; };
    linear_lo.push_back(d(s.linear_lower));
    linear_hi.push_back(d(s.linear_upper));
    // An unbounded (uncertified) position is a gap, and does not set the scale.
    bool bounded = std::isfinite(s.certified.lower) && std::isfinite(s.certified.upper);
    cert_lo.push_back(bounded ? d(s.certified.lower) : nan);
    cert_hi.push_back(bounded ? d(s.certified.upper) : nan);
    rss_lo.push_back(d(s.rss_lower));
    rss_hi.push_back(d(s.rss_upper));
    mc_lo.push_back(s.has_monte_carlo ? d(s.monte_carlo_min) : nan);
    mc_hi.push_back(s.has_monte_carlo ? d(s.monte_carlo_max) : nan);
    if (s.contact) {
      ++held;
      unbounded += !bounded;
      lo = std::min(lo, bounded ? d(s.certified.lower) : d(s.linear_lower));
      hi = std::max(hi, bounded ? d(s.certified.upper) : d(s.linear_upper));
    }
  }
  if (x.empty()) x = {0, 1};
  Frame f = frame_of(x.front(), x.back(), lo, hi, 0.08);
  moved_axis(f.x, file && !r.driver_rotates ? r.length_exponent : 0);
  moved_axis(f.y, file && !r.follower_rotates ? r.length_exponent : 0);
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"960\" height=\"460\" viewBox=\"0 0 960 460\">\n";
  out << axes(f, "Variation of " + r.follower + " about its nominal motion (" + r.model_name + ")",
              r.driver + " (" + axis_unit(r, r.driver_rotates, file) + ")",
              std::string("deviation of ") + r.follower + " (" + axis_unit(r, r.follower_rotates, file) + ")");
  out << polyline(f, x, std::vector<double>(x.size(), 0.0), "stroke=\"#000\" stroke-width=\"1\"");
  out << polyline(f, x, cert_lo, "stroke=\"#c00\" stroke-width=\"1.6\"");
  out << polyline(f, x, cert_hi, "stroke=\"#c00\" stroke-width=\"1.6\"");
  out << polyline(f, x, linear_lo, "stroke=\"#06c\" stroke-width=\"1.2\" stroke-dasharray=\"6 3\"");
  out << polyline(f, x, linear_hi, "stroke=\"#06c\" stroke-width=\"1.2\" stroke-dasharray=\"6 3\"");
  out << polyline(f, x, rss_lo, "stroke=\"#2a2\" stroke-width=\"1\" stroke-dasharray=\"2 2\"");
  out << polyline(f, x, rss_hi, "stroke=\"#2a2\" stroke-width=\"1\" stroke-dasharray=\"2 2\"");
  out << polyline(f, x, mc_lo, "stroke=\"#f90\" stroke-width=\"1.4\"");
  out << polyline(f, x, mc_hi, "stroke=\"#f90\" stroke-width=\"1.4\"");
  // Where the certified band is unbounded the picture has a gap; a line under the title says
  // how many and where to read why (the report's notes: e.g. a chain's hand-over candidate that
  // could not be decided).
  if (unbounded > 0)
    out << "<text x=\"480\" y=\"36\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"11\" "
           "fill=\"#c00\">certified band unbounded at "
        << unbounded << " of " << held << " positions in contact (gaps in the red curves; the notes say why)</text>\n";
  out << legend({{"stroke=\"#c00\" stroke-width=\"2\"", "certified worst case"},
                 {"stroke=\"#06c\" stroke-dasharray=\"6 3\"", "linearised worst case"},
                 {"stroke=\"#2a2\" stroke-dasharray=\"2 2\"", "mean +- 3 sigma"},
                 {"stroke=\"#f90\" stroke-width=\"2\"", "Monte Carlo envelope"}});
  out << "</svg>\n";
  return out.str();
}

std::string zone_svg(const ToleranceResult& r, const std::vector<long>& exponents) {
  const bool file = at_files_scale(exponents);
  // The zone with the widest certified band.
  const ContactZone* zone = nullptr;
  double widest = -1;
  for (const ContactZone& z : r.zones)
    for (std::size_t k = 0; k < z.x.size(); ++k)
      if (z.certified_upper[k] - z.certified_lower[k] > widest) {
        widest = z.certified_upper[k] - z.certified_lower[k];
        zone = &z;
      }
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"960\" height=\"460\" viewBox=\"0 0 960 460\">\n";
  if (!zone) {
    out << "<text x=\"20\" y=\"40\" font-family=\"sans-serif\">no contact zone</text>\n</svg>\n";
    return out.str();
  }
  double uf = unit_factor(zone->y_rotates), xf = unit_factor(zone->x_rotates);
  std::vector<double> x, zero, ll, lu, cl, cu;
  double lo = 0, hi = 0;
  for (std::size_t k = 0; k < zone->x.size(); ++k) {
    x.push_back(zone->x[k] * xf);
    zero.push_back(0);
    ll.push_back((zone->linear_lower[k] - zone->nominal[k]) * uf);
    lu.push_back((zone->linear_upper[k] - zone->nominal[k]) * uf);
    cl.push_back((zone->certified_lower[k] - zone->nominal[k]) * uf);
    cu.push_back((zone->certified_upper[k] - zone->nominal[k]) * uf);
    lo = std::min({lo, cl.back(), ll.back()});
    hi = std::max({hi, cu.back(), lu.back()});
  }
  Frame f = frame_of(x.front(), x.back(), lo, hi, 0.1);
  moved_axis(f.x, file && !zone->x_rotates ? r.length_exponent : 0);
  moved_axis(f.y, file && !zone->y_rotates ? r.length_exponent : 0);
  out << axes(f, "Contact zone (Figure 5 detail): " + zone->contact,
              std::string("x part coordinate (") + axis_unit(r, zone->x_rotates, file) + ")",
              std::string("zone boundary - nominal curve (") + axis_unit(r, zone->y_rotates, file) + ")");
  out << polyline(f, x, zero, "stroke=\"#000\" stroke-width=\"1.2\"");
  out << polyline(f, x, cl, "stroke=\"#c00\" stroke-width=\"1.6\"");
  out << polyline(f, x, cu, "stroke=\"#c00\" stroke-width=\"1.6\"");
  out << polyline(f, x, ll, "stroke=\"#06c\" stroke-width=\"1.2\" stroke-dasharray=\"6 3\"");
  out << polyline(f, x, lu, "stroke=\"#06c\" stroke-width=\"1.2\" stroke-dasharray=\"6 3\"");
  out << legend({{"stroke=\"#000\"", "nominal contact curve"},
                 {"stroke=\"#c00\" stroke-width=\"2\"", "certified zone bounds"},
                 {"stroke=\"#06c\" stroke-dasharray=\"6 3\"", "linearised zone bounds"}});
  out << "</svg>\n";
  return out.str();
}

}  // namespace

std::string tolerance_band_svg(const ToleranceResult& r) { return band_svg(r, {}); }
std::string tolerance_band_svg(const ToleranceResult& r, const std::vector<long>& k) { return band_svg(r, k); }
std::string tolerance_zone_svg(const ToleranceResult& r) { return zone_svg(r, {}); }
std::string tolerance_zone_svg(const ToleranceResult& r, const std::vector<long>& k) { return zone_svg(r, k); }

}  // namespace hipair
