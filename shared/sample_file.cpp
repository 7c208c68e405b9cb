// nscd/shared/sample_file.cpp — see sample_file.hpp.
#include "nscd/shared/sample_file.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd::scenes {
namespace {

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

bool comment_or_blank(const std::string& line) {
  const auto k = line.find_first_not_of(" \t");
  return k == std::string::npos || line[k] == '#';
}

SampleGrain parse_grain(const std::vector<std::string>& t, std::size_t expected_index, const LineReader& r) {
  if (t.size() < 11 || t.size() % 2 == 0)
    r.fail("expected 'index x y radius theta' and at least 3 vertices (x y pairs): 5 + 2n fields with n >= 3, got " +
           std::to_string(t.size()) + " fields");
  SampleGrain g;
  g.line = r.line_number();
  try {
    const long long index = parse_integer(t[0], "index", 0);
    if (static_cast<std::size_t>(index) != expected_index)
      r.fail("grain index " + std::to_string(index) + " out of order: indices run 0, 1, 2, ... and this line must be " +
             std::to_string(expected_index));
    g.centre = {parse_real(t[1], "x"), parse_real(t[2], "y")};
    g.radius = parse_real(t[3], "radius");
    g.theta = parse_real(t[4], "theta");
    for (std::size_t k = 5; k < t.size(); k += 2) {
      const std::string v = "vertex " + std::to_string((k - 5) / 2);
      g.vertices.push_back({parse_real(t[k], v + " x"), parse_real(t[k + 1], v + " y")});
    }
  } catch (const Error& e) {
    if (std::string(e.what()).rfind(r.where(), 0) == 0) throw;
    r.fail(e.what());
  }
  if (!(g.radius > 0.0)) r.fail("radius must be > 0, got " + exact(g.radius));
  if (g.vertices.size() > kMaxPolygVertices) r.fail("too many vertices (at most " + std::to_string(kMaxPolygVertices) + ")");
  try {
    validate_polygon(g.vertices, "grain " + std::to_string(expected_index));
  } catch (const Error& e) {
    r.fail(e.what());
  }
  for (std::size_t k = 0; k < g.vertices.size(); ++k) {
    const Vec2 d = g.vertices[k] - g.centre;
    const double dist = std::hypot(d.x, d.y);
    if (dist > g.radius * (1.0 + 1e-9))
      r.fail("vertex " + std::to_string(k) + " lies " + exact(dist) + " m from the centre, beyond the radius " + exact(g.radius) + " m");
  }
  const Vec2 c = mass_properties(g.vertices).centroid;
  const double off = std::hypot(c.x - g.centre.x, c.y - g.centre.y);
  if (off > 1e-6 * g.radius)
    r.fail("the vertices' centroid (" + exact(c.x) + ", " + exact(c.y) + ") is " + exact(off) +
           " m from the centre: x y must be the centre of mass (within 1e-6 radius)");
  return g;
}

}  // namespace

std::vector<SampleGrain> parse_sample_text(std::string text, const std::filesystem::path& file) {
  LineReader r(std::move(text), file, "sample file");
  std::vector<SampleGrain> out;
  for (std::string line; r.next(line);) {
    for (char ch : line)
      if ((static_cast<unsigned char>(ch) < 0x20 && ch != '\t') || ch == 0x7f) r.fail("control character in the line");
    if (comment_or_blank(line)) continue;
    out.push_back(parse_grain(tokens(line), out.size(), r));
  }
  if (out.empty()) throw Error("sample file '" + file.string() + "': no grain (one line per grain: index x y radius theta vertices)");
  return out;
}

std::vector<SampleGrain> read_sample_file(const std::filesystem::path& file) {
  LineReader r = LineReader::from_file(file, "sample file");
  std::string text, line;
  while (r.next(line)) text += line + "\n";
  return parse_sample_text(std::move(text), file);
}

std::vector<BodyId> add_sample_grains(Registry& reg, MaterialId material, std::span<const SampleGrain> grains) {
  std::vector<BodyId> out;
  out.reserve(grains.size());
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const SampleGrain& g = grains[i];
    // shape frame: the vertices about the centre, unrotated by theta; the body is then placed
    // at the centre with angle theta, which puts every vertex back where the file has it
    const double c = std::cos(g.theta), s = std::sin(g.theta);
    Polygon local;
    local.reserve(g.vertices.size());
    for (const Vec2& v : g.vertices) {
      const Vec2 d = v - g.centre;
      local.push_back({c * d.x + s * d.y, -s * d.x + c * d.y});
    }
    out.push_back(add_polygon_body(reg, local, material, g.centre, g.theta, "grain " + std::to_string(i)));
  }
  return out;
}

}  // namespace nscd::scenes
