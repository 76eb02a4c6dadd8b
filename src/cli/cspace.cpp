// `hipair cspace MODEL [--pair A:B] [--svg OUT.svg] [--json OUT.json] [--stats]`: builds the
// exact configuration space of a pair (or of every fixed-axis pair) and writes it as a
// picture (paper Figure 2 style) and as JSON (cells, edges with feature pairs and exact
// polynomials, vertices with exact coordinates). 3-DOF pairs (a planar part against a fixed
// part) are sliced: a stack of slices and the cell structure (cli/cspace_sliced.cpp).
#include "cli/commands.hpp"
#include "cli/cspace_json.hpp"
#include "cli/cspace_pinslot.hpp"
#include "cli/cspace_sliced.hpp"
#include "core/model_scale.hpp"

#include "io/atomic_file.hpp"
#include "io/output_paths.hpp"
#include "render/cspace_svg.hpp"
#include "render/pinslot_svg.hpp"
#include "render/sliced_svg.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include <mpfi.h>
#include <mpfr.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <unistd.h>

namespace hipair::cli {
namespace {

struct CSpaceCommandOptions {
  std::string model;
  std::string pair;
  std::string svg;
  std::string json;
  bool stats = false;
  bool spurious = false;
  bool aggregated = false;
  bool algebraic_traits = false;
  std::size_t quadratic_max_bits = CSpaceBuildOptions{}.quadratic_max_coefficient_bits;
  std::vector<std::string> overrides;
  bool allow_out_of_tolerance = false;
  std::string rounding;
  std::string region = "full";
  unsigned tiles = 0;
  std::size_t slices = 0;
  bool plane_witnesses = false;
  std::vector<std::size_t> full_slices;   // 3-DOF pairs: slices drawn at full size
  std::vector<std::string> at, to;         // pin-in-slot pairs: a path's ends (--at, --to)
  std::set<std::string> given;             // the long options given on the command line
};

// Options that apply to one kind of pair only, or to one output, are refused when the pairs built
// have none of that kind or the output is not asked for (session 45: `--full-slices` on a
// fixed-axis pair, `--slices` on a pair without a pin-slot part, `--tiles` without `--region
// operating` were taken and ignored). Checked before any C-space is built.
void refuse_options_that_do_not_apply(const CSpaceCommandOptions& options, bool fixed_axis, bool sliced, bool pin_slot) {
  auto refuse = [&](const char* option, const std::string& why) {
    if (options.given.count(option)) throw ModelError("", std::string(option) + ": " + why);
  };
  std::string pairs = options.pair.empty() ? "the model has no " : "the pair " + options.pair + " is no ";
  if (!sliced) refuse("--full-slices", "applies to 3-DOF pairs (a planar part against a fixed part); " + pairs + "such pair");
  if (!pin_slot) {
    refuse("--slices", "applies to pin-in-slot pairs; " + pairs + "such pair");
    refuse("--plane-witnesses", "applies to pin-in-slot pairs; " + pairs + "such pair");
    refuse("--at", "a path's start, for pin-in-slot pairs; " + pairs + "such pair");
    refuse("--to", "a path's end, for pin-in-slot pairs; " + pairs + "such pair");
  }
  if (!options.to.empty() && (fixed_axis || sliced))
    refuse("--to", "a path is planned through one pin-in-slot pair's stack: give --pair OTHER:PIN");
  if (options.to.empty()) refuse("--at", "the start of a path to --to: give --to");
  if (!fixed_axis)
    for (const char* option : {"--region", "--tiles", "--spurious", "--aggregated", "--algebraic-traits", "--quadratic-max-bits"})
      refuse(option, "applies to pairs of rotating or translating parts (fixed-axis pairs); " + pairs + "such pair");
  if (options.region != "operating") refuse("--tiles", "the tiles of --region operating: give --region operating");
  if (options.svg.empty()) {
    refuse("--full-slices", "chooses the slices --svg draws at full size: give --svg");
    refuse("--spurious", "draws spurious edges in --svg: give --svg");
  }
}

void print_statistics(const CSpace& space) {
  const CSpaceStatistics& s = space.statistics();
  std::printf("pair %s:%s (%d-D, %zu charts)\n", space.first_part().c_str(), space.second_part().c_str(),
              space.dimension(), s.charts);
  std::printf("  feature pairs considered %zu, culled %zu; curves %zu; pieces inserted %zu\n",
              s.feature_pairs_considered, s.feature_pairs_culled, s.curves, s.pieces_inserted);
  std::printf("  vertices %zu, edges %zu (contact %zu), faces %zu, cells %zu\n", s.vertices, s.edges, s.contact_edges,
              s.faces, s.cells);
  if (s.circle_segment_charts > 0)
    std::printf("  circle-segment arrangements (lines and circles): %zu of %zu charts\n", s.circle_segment_charts,
                s.charts);
  if (s.quadratic_charts > 0)
    std::printf("  quadratic-traits arrangements (degree <= 2 in y): %zu of %zu charts\n", s.quadratic_charts, s.charts);
  if (s.touching_edges + s.touching_vertices + s.touching_undecided > 0)
    std::printf("  zero-clearance contacts: %zu touching edges, %zu isolated touching vertices%s\n", s.touching_edges,
                s.touching_vertices,
                s.touching_undecided ? (", " + std::to_string(s.touching_undecided) +
                                        " not decided in blocked space (coincident-curve edges and vertices the exact oracle cannot pose; unchecked)")
                                           .c_str()
                                     : "");
  if (!space.complete())
    std::printf("  operating region: %zu tiles, %zu quadtree cells flooded in %.1f ms (outside it nothing is claimed)\n",
                s.region_tiles, s.region_cells, s.seconds_region * 1e3);
  std::printf("  time (ms): curves %.1f, culling %.1f, clipping %.1f, arrangement %.1f, export %.1f, labelling %.1f, "
              "classification %.1f, cells %.1f, total %.1f\n",
              s.seconds_curves * 1e3, s.seconds_culling * 1e3, s.seconds_clipping * 1e3, s.seconds_arrangement * 1e3, s.seconds_export * 1e3,
              s.seconds_labelling * 1e3, s.seconds_classification * 1e3, s.seconds_cells * 1e3,
              s.seconds_total * 1e3);
}

// A part name as a piece of a file name: letters, digits, '-' and '_' kept, anything else
// (a '/', a '.', a space) becomes '-', so a name never leaves the output's directory.
std::string file_name_part(const std::string& text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '-';
  return out;
}

std::filesystem::path suffixed(const std::string& path, const std::string& first, const std::string& second,
                               bool several) {
  if (!several) return path;
  std::filesystem::path p(path);
  std::string stem = p.stem().string() + "-" + file_name_part(first) + "-" + file_name_part(second);
  return p.parent_path() / (stem + p.extension().string());
}

std::filesystem::path suffixed(const std::string& path, const CSpace& space, bool several) {
  return suffixed(path, space.first_part(), space.second_part(), several);
}

std::filesystem::path suffixed(const std::string& path, const SlicedSpace& space, bool several) {
  return suffixed(path, space.fixed_part(), space.free_part(), several);
}

// An operating region is the channel of the initial configuration. Its build refuses a seed whose
// quadtree cell is certainly blocked ("the parts certainly overlap at the seed configuration",
// exit 3), but a start that overlaps by less than a quadtree cell was built as a region around a
// blocked start (a 13 x 14 gear pair at zero backlash: one blocked cell; a lever 10^-3 mm into a
// turning stop: a free and a blocked cell), exit 0 (session 45). The built region now decides
// the start exactly: where its coordinates are exact rationals (a rotation at angle 0, any
// translation offset), located in a blocked cell (or on a curve piece inside one), the same
// error. Since session 46 also at any other initial angle (a rational angle has a transcendental
// half-angle tangent, never a point of contact space) and in a 1-D region: the tangent is
// enclosed in a rational interval of width about 2^-240 (MPFI); the start lies in the blocked
// cell B when an end of the interval (a corner of the box of both enclosures) lies inside B,
// the sides of the interval (the box) cross no real edge (CSpace::first_crossing, exact), and,
// in 2-D, no vertex of a real edge of the chart can lie inside the box (then no curve of contact
// space enters it: B holds the whole box). An enclosure that does not decide (a start within
// 2^-240 of contact space, or across a chart side) is left to the build's own test, as before.
struct StartCoordinate {
  PartCoordinate lo, hi;   // equal when exact
  bool exact = true;
};

std::optional<StartCoordinate> start_coordinate(const Part& part) {
  if (part.motion.kind == Motion::Kind::translation)
    return StartCoordinate{{PartCoordinate::Kind::offset, part.initial.offset}, {PartCoordinate::Kind::offset, part.initial.offset}};
  if (part.motion.kind != Motion::Kind::rotation) return std::nullopt;
  if (sgn(part.initial.angle) == 0)
    return StartCoordinate{{PartCoordinate::Kind::half_angle_tangent, Rational(0)}, {PartCoordinate::Kind::half_angle_tangent, Rational(0)}};
  // tan(theta / 2) enclosed (a tangent near its pole: no finite enclosure, undecided)
  mpfi_t t;
  mpfi_init2(t, 256);
  mpfi_set_q(t, part.initial.angle.get_mpq_t());
  mpfi_div_2ui(t, t, 1);
  mpfi_tan(t, t);
  std::optional<StartCoordinate> result;
  if (!mpfi_nan_p(t) && !mpfi_inf_p(t) && mpfi_bounded_p(t)) {
    mpfr_t end;
    mpfr_init2(end, 256);
    Rational lo, hi;
    mpfi_get_left(end, t);
    mpfr_get_q(lo.get_mpq_t(), end);
    mpfi_get_right(end, t);
    mpfr_get_q(hi.get_mpq_t(), end);
    mpfr_clear(end);
    if (lo < hi && Rational(hi - lo) < Rational(1, mpz_class(1) << 200) * (1 + abs(lo)))
      result = StartCoordinate{{PartCoordinate::Kind::half_angle_tangent, lo}, {PartCoordinate::Kind::half_angle_tangent, hi}, false};
  }
  mpfi_clear(t);
  return result;
}

bool in_blocked_cell(const CSpace& space, const Location& location) {
  return location.kind == Location::Kind::blocked ||
         ((location.kind == Location::Kind::edge || location.kind == Location::Kind::vertex) && location.cell != no_index &&
          space.cells()[location.cell].kind == CellKind::blocked);
}

// Whether the start certainly lies in blocked space of `space` (false: free, touching, or not
// decided by the enclosures).
bool start_in_blocked_space(const CSpace& space, const StartCoordinate& x, const StartCoordinate& y) {
  if (x.exact && y.exact) return in_blocked_cell(space, space.locate(x.lo, y.lo));
  auto corner = [&](bool x_hi, bool y_hi) { return space.to_chart(x_hi ? x.hi : x.lo, y_hi ? y.hi : y.lo); };
  std::optional<ChartPoint> a = corner(false, false), b = corner(true, false), c = corner(true, true), d = corner(false, true);
  if (!a || !b || !c || !d || a->chart != b->chart || a->chart != c->chart || a->chart != d->chart) return false;
  Location start = space.locate(*a);
  if (start.kind != Location::Kind::blocked) return false;
  try {
    // the box's sides (a segment in 1-D, or when one coordinate is exact)
    std::vector<ChartPoint> corners{*a, *b};
    if (space.dimension() == 2 && !y.exact) corners = {*a, *b, *c, *d, *a};
    for (std::size_t k = 0; k + 1 < corners.size(); ++k)
      if (corners[k].x != corners[k + 1].x || corners[k].y != corners[k + 1].y)
        if (space.first_crossing(corners[k], corners[k + 1].x, corners[k + 1].y).found) return false;
  } catch (const GeometryError&) {   // a side outside the built tiles
    return false;
  }
  if (space.dimension() == 2 && !x.exact && !y.exact) {
    // no vertex of a real edge of this chart inside the box (by its isolating bounds)
    const Rational &x_lo = std::min(a->x, c->x), &x_hi = std::max(a->x, c->x), &y_lo = std::min(a->y, c->y), &y_hi = std::max(a->y, c->y);
    for (const CSpaceVertex& vertex : space.vertices()) {
      bool real = false;
      for (std::size_t e : vertex.edges) real = real || (space.edges()[e].real && space.edges()[e].chart == a->chart);
      if (!real) continue;
      const Rational &vx_lo = vertex.x.lower, &vx_hi = vertex.x.exact ? vertex.x.lower : vertex.x.upper;
      Rational vy_lo = vertex.y_exact && vertex.y.exact ? vertex.y.lower : vertex.y_lower;
      Rational vy_hi = vertex.y_exact && vertex.y.exact ? vertex.y.lower : vertex.y_upper;
      bool outside = vx_hi < x_lo || vx_lo > x_hi || vy_hi < y_lo || vy_lo > y_hi;
      if (!outside) return false;
    }
  }
  return true;
}

void refuse_blocked_start(const Model& model, const CSpace& space) {
  auto coordinate = [&](const std::string& name) -> std::optional<StartCoordinate> {
    auto index = model.find_part(name);
    if (!index) return std::nullopt;
    return start_coordinate(model.parts[*index]);
  };
  std::optional<StartCoordinate> x = coordinate(space.x_part()), y;
  if (space.dimension() == 2) y = coordinate(space.y_part());
  else y = StartCoordinate{};
  if (!x || !y) return;
  if (start_in_blocked_space(space, *x, *y))
    throw GeometryError("operating region of '" + space.first_part() + "' and '" + space.second_part() +
                        "': the parts certainly overlap at the seed configuration (the initial configuration lies in "
                        "blocked space of the exact C-space built around it: there is no channel to build)");
}

// The same refusal before the build, where it is decided at once (session 65, perf65): both
// parts' start coordinates exact (a rotation at angle 0, a translation offset, a fixed part) and
// the exact overlap predicate (part_overlap) finds their interiors meeting there. The region
// built around such a start would locate it in a blocked cell (the C-space is exact), so the
// answer is the one refuse_blocked_start gives after the build; only the build is saved: a 19 x 40
// spur-gear pair at zero backlash (coprime tooth counts: its channel is every tooth meeting
// every tooth, 8 058 tiles) built for 38 s to learn that its start overlaps. Touching or apart
// (or an inexact coordinate): the build and its own test decide, as before.
// A mechanism drawn at an extreme scale is decided on its copy divided exactly by 10^E
// (kinematic_decimal_exponent, as `analyze` runs it): the relation is the same (a similarity;
// the start's half-angle tangents do not change, offsets are scaled with the lengths), and the
// predicate's numbers are ordinary ones (at 10^400 mm the model's own took 0.65 s for a
// 17 x 17 pair whose start is free, a quarter of its region build).
void refuse_overlapping_start(const Model& given, std::size_t first, std::size_t second) {
  const long exponent = kinematic_decimal_exponent(given);
  const Model scaled = exponent != 0 ? decimal_scaled_model(given, exponent) : Model();
  const Model& model = exponent != 0 ? scaled : given;
  auto placement = [&](std::size_t index) -> std::optional<Placement> {
    const Part& part = model.parts[index];
    if (part.motion.kind == Motion::Kind::fixed) return Placement{};
    std::optional<StartCoordinate> start = start_coordinate(part);
    if (!start || !start->exact) return std::nullopt;
    return part_placement(part, start->lo);
  };
  std::optional<Placement> a = placement(first), b = placement(second);
  if (!a || !b) return;
  if (part_overlap(model.parts[first], *a, model.parts[second], *b).relation != PartRelation::overlapping) return;
  throw GeometryError("operating region of '" + model.parts[first].name + "' and '" + model.parts[second].name +
                      "': the parts certainly overlap at the seed configuration (their interiors meet at the "
                      "initial configuration, by the exact overlap predicate: there is no channel to build)");
}

int run(const CSpaceCommandOptions& options) {
  // Refused before the (possibly long) build when the paths are used as given; the suffixed
  // names of several pairs are checked again below, before anything is written.
  io::refuse_overwriting_inputs({{options.svg, "--svg"}, {options.json, "--json"}}, {options.model});
  io::refuse_unusable_output_files({{options.svg, "--svg"}, {options.json, "--json"}});
  auto rounding = rounding_scope(options.rounding);
  ReadOptions overrides = parameter_overrides(options.overrides, options.allow_out_of_tolerance);
  refuse_unknown_parameters(options.model, options.overrides, "--set");
  Model model = read_model_file(options.model, overrides);
  CSpaceBuildOptions build;
  if (isatty(2)) build.progress = stderr_progress();
  build.aggregated_insertion = options.aggregated;
  build.quadratic_traits = !options.algebraic_traits;
  build.quadratic_max_coefficient_bits = options.quadratic_max_bits;
  build.operating_region = options.region == "operating";
  build.region_tiles = options.tiles;
  // a translating pair beyond the doubles' range (1e400 mm): built in units of 2^L mm, its
  // JSON written in mm (cspace_json.cpp), its SVG drawn in those units (the title says so)
  build.normalise_lengths = true;
  std::vector<CSpace> spaces;
  // 3-DOF pairs (a planar part against a fixed part): sliced C-spaces (docs/cspace.md)
  std::vector<std::pair<std::string, std::string>> sliced_requests;
  std::vector<std::pair<std::string, std::string>> pin_requests;   // (other, pin_slot part)
  if (!options.pair.empty()) {
    auto colon = options.pair.find(':');
    if (colon == std::string::npos) throw ModelError("", "--pair expects FIRST:SECOND, got '" + options.pair + "'");
    std::string first = options.pair.substr(0, colon), second = options.pair.substr(colon + 1);
    // the option named, with the parts there are (until session 44 "/parts: no part called 'x'"
    // and "/pairs: a pair needs two different parts" named no option)
    for (const std::string& name : {first, second})
      if (!model.find_part(name)) {
        std::string names;
        for (const Part& part : model.parts) names += (names.empty() ? "'" : ", '") + part.name + "'";
        throw ModelError("", "--pair " + options.pair + ": no part called '" + name + "' (the parts: " + names + ")");
      }
    if (first == second) throw ModelError("", "--pair " + options.pair + ": a pair needs two different parts");
    require_feature_spread(model, *model.find_part(first), *model.find_part(second));   // before work (session 53)
    // a planar part against a moving part: one message naming the pair (until session 58 "part
    // 'peg' moves with more than one degree of freedom; its pair is not a fixed-axis pair")
    if (auto refusal = planar_pair_not_built(model, *model.find_part(first), *model.find_part(second)))
      throw GeometryError(*refusal);
    if (auto sliced = sliced_pair(model, first, second)) {
      refuse_options_that_do_not_apply(options, false, true, false);
      sliced_requests.push_back(*sliced);
    } else if (auto pin = pin_slot_pair(model, first, second)) {
      refuse_options_that_do_not_apply(options, false, false, true);
      pin_requests.push_back(*pin);
    } else {
      refuse_options_that_do_not_apply(options, true, false, false);
      if (build.operating_region) refuse_overlapping_start(model, *model.find_part(first), *model.find_part(second));
      spaces.push_back(CSpace::build(model, first, second, build));
      if (build.operating_region) refuse_blocked_start(model, spaces.back());
    }
  } else {
    require_feature_spread(model);   // every pair, before work (session 53)
    sliced_requests = sliced_pairs(model);
    pin_requests = pin_slot_pairs(model);
    // (a fixed-axis pair: at most one degree of freedom per part, one at least, as
    // CSpace::build_all takes them)
    bool fixed_axis = false;
    for (const PairSpec& pair : model.pairs) {
      int a = model.parts[pair.first].motion.degrees_of_freedom(), b = model.parts[pair.second].motion.degrees_of_freedom();
      fixed_axis = fixed_axis || (a <= 1 && b <= 1 && a + b > 0);
    }
    refuse_options_that_do_not_apply(options, fixed_axis, !sliced_requests.empty(), !pin_requests.empty());
    // (the pairs CSpace::build_all builds, in its order)
    if (build.operating_region)
      for (const PairSpec& pair : model.pairs) {
        int a = model.parts[pair.first].motion.degrees_of_freedom(), b = model.parts[pair.second].motion.degrees_of_freedom();
        if (a <= 1 && b <= 1 && a + b > 0) refuse_overlapping_start(model, pair.first, pair.second);
      }
    spaces = CSpace::build_all(model, build);
    if (build.operating_region)
      for (const CSpace& space : spaces) refuse_blocked_start(model, space);
    if (spaces.empty() && sliced_requests.empty() && pin_requests.empty()) {
      // the first pair of a planar part against a moving part, named (session 58)
      std::string unbuilt;
      for (const PairSpec& pair : model.pairs)
        if (auto refusal = planar_pair_not_built(model, pair.first, pair.second)) {
          unbuilt = "; " + *refusal;
          break;
        }
      // (where: the pairs, /pairs; an empty list said nothing of where, session 61)
      throw GeometryError("the model's pairs (/pairs" + std::string(model.pairs.empty() ? ", empty" : "") +
                          ") hold no fixed-axis pair with a moving part, no 3-DOF pair (a planar part "
                          "against a fixed part) and no pin-in-slot pair" + unbuilt);
    }
  }
  std::vector<SlicedSpace> sliced_spaces;
  for (const auto& [fixed, free] : sliced_requests)
    sliced_spaces.push_back(build_sliced(model, fixed, free, isatty(2)));
  // Pin-in-slot stacks of a mechanism drawn at an extreme scale (lengths outside about 1e-9 ..
  // 1e9 mm) are built, as `analyze` runs it, on the model divided exactly by 10^E
  // (kinematic_decimal_exponent): a model written at 10^E times an ordinary one gets that one's
  // stack, its lengths written in mm times 10^E exactly (session 54; the slices' samples and
  // witnesses differed with the power-of-two unit, and a stack at 10^-300 took 4 x as long).
  // a path's ends (--at/--to), read before the build: one pin-in-slot pair
  std::optional<PinSlotPathEnds> path_ends;
  if (!options.to.empty()) {
    if (pin_requests.size() != 1)
      throw ModelError("", "--to: a path is planned through one pin-in-slot pair's stack, and the model has " +
                               std::to_string(pin_requests.size()) + ": give --pair OTHER:PIN");
    path_ends = pin_slot_path_ends(model, pin_requests[0].first, pin_requests[0].second, options.at, options.to);
  }
  std::vector<PinSlotSpace> pin_spaces;
  const long pin_exponent = pin_requests.empty() ? 0 : kinematic_decimal_exponent(model);
  const Model pin_model = pin_exponent != 0 ? decimal_scaled_model(model, pin_exponent) : Model();
  for (const auto& [other, pin] : pin_requests)
    pin_spaces.push_back(build_pin_slot(pin_exponent != 0 ? pin_model : model, other, pin, isatty(2), options.slices,
                                        options.plane_witnesses));
  bool several = spaces.size() + sliced_spaces.size() + pin_spaces.size() > 1;
  std::vector<io::PlannedOutput> outputs;
  for (const CSpace& space : spaces) {
    if (!options.svg.empty()) outputs.push_back({suffixed(options.svg, space, several), "--svg"});
    if (!options.json.empty()) outputs.push_back({suffixed(options.json, space, several), "--json"});
  }
  for (const SlicedSpace& space : sliced_spaces) {
    if (!options.svg.empty()) outputs.push_back({suffixed(options.svg, space, several), "--svg"});
    if (!options.json.empty()) outputs.push_back({suffixed(options.json, space, several), "--json"});
  }
  for (const PinSlotSpace& space : pin_spaces) {
    if (!options.svg.empty())
      outputs.push_back({suffixed(options.svg, space.other_part(), space.pin_slot_part(), several), "--svg"});
    if (!options.json.empty())
      outputs.push_back({suffixed(options.json, space.other_part(), space.pin_slot_part(), several), "--json"});
  }
  io::refuse_overwriting_inputs(outputs, {options.model});
  // the path (its ends checked: outside the limits, blocked or touching is refused, exit 2,
  // before anything is written)
  std::optional<PinSlotPath> path;
  if (path_ends) {
    for (const std::string& note : path_ends->notes) std::printf("%s\n", note.c_str());
    path = pin_slot_path(pin_spaces.front(), *path_ends, pin_exponent);
  }
  // every document is made before any is written: a failure leaves no partial output
  std::vector<std::pair<std::filesystem::path, std::string>> sliced_documents;
  for (const SlicedSpace& space : sliced_spaces) {
    if (options.stats) print_sliced_statistics(space);
    if (!options.svg.empty()) {
      render::SlicedSvgOptions svg;
      svg.full_size = options.full_slices;
      svg.title = model.name + ": sliced C-space of " + space.free_part() + " against " + space.fixed_part() + " (" +
                  std::to_string(space.critical_angles().size()) + " critical angles, " +
                  std::to_string(space.intervals().size()) + " slices, " + std::to_string(space.components()) +
                  (space.components() == 1 ? " free component)" : " free components)");
      if (long unit = space.length_unit_exponent(); unit != 0)
        svg.title += " (offsets in units of 2^" + std::to_string(unit) + " mm)";
      sliced_documents.emplace_back(suffixed(options.svg, space, several), render::sliced_stack_svg(space, svg));
    }
    if (!options.json.empty()) sliced_documents.emplace_back(suffixed(options.json, space, several), sliced_json(space, options.stats));
  }
  for (const PinSlotSpace& space : pin_spaces) {
    if (options.stats) print_pin_slot_statistics(space);
    if (!options.svg.empty()) {
      render::PinSlotSvgOptions svg;
      svg.title = model.name + ": pin-in-slot C-space of " + space.pin_slot_part() + " against " + space.other_part() +
                  " (" + std::to_string(space.slices().size()) + " slices, " +
                  std::to_string(space.changes().size()) + (space.changes().size() == 1 ? " change" : " changes") +
                  " isolated, " + std::to_string(space.groups()) +
                  (space.groups() == 1 ? " certainly-connected group)" : " certainly-connected groups)");
      if (long unit = space.length_unit_exponent(); unit != 0)
        svg.title += " (slides in units of 2^" + std::to_string(unit) + " mm)";
      if (pin_exponent != 0) svg.title += " (slides in units of 1e" + std::to_string(pin_exponent) + " mm)";
      if (path) svg.path = &*path;
      sliced_documents.emplace_back(suffixed(options.svg, space.other_part(), space.pin_slot_part(), several),
                                    render::pin_slot_stack_svg(space, svg));
    }
    if (!options.json.empty())
      sliced_documents.emplace_back(suffixed(options.json, space.other_part(), space.pin_slot_part(), several),
                                    pin_slot_json(space, options.stats, pin_exponent, path ? &*path : nullptr));
  }
  for (const CSpace& space : spaces) {
    if (options.stats) print_statistics(space);
    if (!options.svg.empty()) {
      render::CSpaceSvgOptions svg;
      svg.show_spurious = options.spurious;
      svg.title = model.name + ": C-space of " + space.first_part() + " / " + space.second_part();
      const long unit = space.length_unit_exponent();
      if (unit != 0) svg.title += " (offsets in units of 2^" + std::to_string(unit) + " mm)";
      // the part's initial coordinate in the space's units (an offset / 2^unit, exactly)
      auto initial = [unit](const Part& part) {
        if (part.motion.kind != Motion::Kind::translation) return part.initial.angle.get_d();
        return times_power_of_two(part.initial.offset, -unit).get_d();
      };
      auto x_index = model.find_part(space.x_part());
      render::CSpaceMark mark;
      mark.label = "initial";
      if (x_index) mark.x = initial(model.parts[*x_index]);
      if (space.dimension() == 2) {
        auto y_index = model.find_part(space.y_part());
        if (y_index) mark.y = initial(model.parts[*y_index]);
      }
      svg.marks.push_back(mark);
      io::write_file_atomically(suffixed(options.svg, space, several), render::cspace_svg(space, svg));
    }
    if (!options.json.empty())
      io::write_file_atomically(suffixed(options.json, space, several),
                                [&](std::ostream& out) { write_space_json(out, space, options.stats); });
  }
  for (const auto& [file, document] : sliced_documents) io::write_file_atomically(file, document);
  if (path) {
    // a path not found (or not shown connected) is a result, written with its status: exit 1
    std::printf("%s\n", pin_slot_path_summary(pin_spaces.front(), *path).c_str());
    return path->status == PinSlotPath::Status::found ? 0 : 1;
  }
  return 0;
}

}  // namespace

void register_cspace(CLI::App& app, Action& action) {
  auto options = std::make_shared<CSpaceCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "cspace", "Build the exact configuration space of a pair (or of every fixed-axis pair and 3-DOF pair) and write it as SVG/JSON");
  command->add_option("model", options->model, "Model file (JSON)")->required()->check(CLI::ExistingFile);
  command->add_option("--pair", options->pair, "The pair FIRST:SECOND (default: every fixed-axis pair and every 3-DOF pair)");
  command->add_option("--svg", options->svg, "SVG picture (blocked shaded, contact curves coloured by feature pair; 3-DOF pairs: a stack of slices)")
      ->check(output_path());
  command->add_option("--json", options->json, "JSON: cells, edges (feature pair, exact polynomial), vertices; 3-DOF pairs: critical angles, slices, free cells, crossings, components")
      ->check(output_path());
  command->add_flag("--stats", options->stats, "Print counts and times per stage");
  command->add_option("--full-slices", options->full_slices,
                      "3-DOF pairs: slices (indices, in order of the angle) drawn again at full size below the stack "
                      "(default: the two either side of the critical angle nearest 0 where the free cells change; without one, up to two "
                      "with the most free cells)")
      ->delimiter(',')
      ->check([](const std::string& index) {   // "-1" wrapped to 18446744073709551615 in the message
        bool digits = !index.empty() && index.find_first_not_of("0123456789") == std::string::npos;
        return digits ? std::string() : "'" + index + "' is not a slice index (0, 1, 2, ...)";
      });
  command->add_flag("--spurious", options->spurious, "Also draw spurious edges (curves through free or blocked space)");
  command->add_flag("--aggregated", options->aggregated, "Insert the quadratic stage's curves by one sweep (for measurements; the algebraic stage always sweeps)");
  command->add_flag("--algebraic-traits", options->algebraic_traits,
                    "Build every chart on CGAL's algebraic traits, also those whose curves have degree <= 2 in y "
                    "(the filtered quadratic traits otherwise; for comparisons)");
  command->add_option("--quadratic-max-bits", options->quadratic_max_bits,
                      "The quadratic traits declines charts with a coefficient above this many bits (default 1024, "
                      "which takes the spur gears' 247-653-bit coefficients; 200 keeps them on the algebraic traits)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}));
  command->add_option("--region", options->region,
                      "full: the whole C-space (default); operating: only the channel containing the initial "
                      "configuration, built tile by tile (gear pairs: linear in the tooth count)")
      ->check(CLI::IsMember({"full", "operating"}));
  command->add_option("--tiles", options->tiles, "Operating region: tiles per chart axis (default: automatic)")
      ->check(CLI::Range(0u, 128u));
  command->add_option("--slices", options->slices,
                      "Pin-in-slot pairs: slices of the stack across the pin-slot part's angle range (default 16)")
      ->check(CLI::Range(std::size_t{2}, std::size_t{256}));
  command->add_flag("--plane-witnesses", options->plane_witnesses,
                    "Pin-in-slot pairs: also join cells of neighbouring slices through paths at constant slide "
                    "(one 2-D C-space per slide tried; slower, connects more)");
  command->add_option("--at", options->at,
                      "Pin-in-slot pairs: the start of a path to --to: PIN=SLIDE,ANGLE and OTHER=VALUE (an angle in rad "
                      "or NNdeg, an offset or slide in mm; default the model's initial configuration)");
  command->add_option("--to", options->to,
                      "Pin-in-slot pairs: plan a path from --at to PIN=SLIDE,ANGLE (and OTHER=VALUE; what is left out "
                      "stays as at the start), written into --json and drawn on --svg; exit 1 when none is found");
  add_parameter_options(command, options->overrides, options->allow_out_of_tolerance);
  add_rounding_option(command, options->rounding);
  command->callback([options, &action, command] {
    options->given = given_options(*command);
    action = [options] { return run(*options); };
  });
}

}  // namespace hipair::cli
