#include "semantic_edge_vo/synthetic/materials.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/synthetic/noise.h"
#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

using Colour = Eigen::Vector3f;

/// A number in [0, 1) fixed by the variant bits and a salt.
float pick(std::uint32_t variant, std::uint32_t salt) {
  return static_cast<float>(mix64((static_cast<std::uint64_t>(variant) << 16) ^ salt) >> 40) * (1.0f / 16777216.0f);
}

Colour lerp(const Colour& a, const Colour& b, float t) { return a + (b - a) * t; }

/// Coverage of the single interval [start, start + width] over the pixel.
float band(double x, double start, double width, double footprint) {
  return intervalCoverage(x, start, width, footprint);
}

float noise(const ShadingPoint& p, double period, int octaves, std::uint32_t salt) {
  return fractalNoise(p.a, p.b, period, octaves, p.footprint, p.variant * 7919u + salt);
}

Colour asphalt(const ShadingPoint& p, const RoadProfile& road) {
  const float grain = fractalNoise(p.a, p.b, 0.3, 3, p.footprint, 11);
  const float patches = fractalNoise(p.a, p.b, 7.0, 2, p.footprint, 12);
  const float tracks = band(std::abs(std::abs(p.a) - road.ego_lane_offset), 0.5, 0.5, p.footprint_a);
  const float level = 0.27f + 0.14f * (grain - 0.5f) + 0.10f * (patches - 0.5f) - 0.03f * tracks;
  float paint = 0.0f;
  for (const LaneLine& line : road.lines) {
    const float across = band(p.a, line.offset - 0.5 * line.width, line.width, p.footprint_a);
    if (across <= 0.0f) continue;
    const float along = line.dash > 0.0 ? pulseCoverage(p.b, line.dash + line.gap, line.dash, p.footprint_b) : 1.0f;
    paint = std::max(paint, across * along);
  }
  if (paint > 0.0f) paint *= 0.8f + 0.2f * fractalNoise(p.a, p.b, 1.0, 2, p.footprint, 13);
  return lerp(Colour(level, level, level * 1.02f), Colour(0.85f, 0.85f, 0.82f), paint);
}

Colour sidewalk(const ShadingPoint& p) {
  const float joints = std::max(pulseCoverage(p.a, 0.6, 0.015, p.footprint_a), pulseCoverage(p.b, 0.6, 0.015, p.footprint_b));
  const float stain = noise(p, 2.0, 3, 21);
  return lerp(Colour(0.58f, 0.55f, 0.50f) * (0.8f + 0.4f * stain), Colour(0.30f, 0.29f, 0.27f), joints);
}

/// The choices a facade's variant bits make, computed once per variant (kept in a small cache: a
/// facade covers many pixels and these take a dozen hashes).
struct FacadeLayout {
  std::uint32_t variant = 0;
  bool house = false, valid = false;
  int style = 0;  // 0 brick, 1 plaster, 2 concrete panels
  Colour wall, frame;
  double floor_height = 3.0, spacing = 3.0, width = 1.4, height = 1.5;
};

const FacadeLayout& facadeLayout(std::uint32_t v, bool house) {
  static const Colour kPlaster[] = {{0.80f, 0.76f, 0.62f}, {0.72f, 0.70f, 0.68f}, {0.78f, 0.62f, 0.48f},
                                    {0.62f, 0.66f, 0.70f}, {0.85f, 0.83f, 0.78f}, {0.55f, 0.52f, 0.48f}};
  thread_local FacadeLayout cache[256];
  FacadeLayout& layout = cache[(v ^ (v >> 8) ^ (house ? 0x5au : 0u)) & 255u];
  if (layout.valid && layout.variant == v && layout.house == house) return layout;
  layout.variant = v;
  layout.house = house;
  layout.valid = true;
  layout.style = house ? 1 : static_cast<int>(pick(v, 1) * 3.0f);
  layout.wall = layout.style == 0 ? Colour(Colour(0.46f, 0.24f, 0.16f) * (0.75f + 0.5f * pick(v, 2)))
                                  : kPlaster[static_cast<int>(pick(v, 4) * 6.0f)];
  layout.frame = pick(v, 10) < 0.6f ? Colour(0.80f, 0.80f, 0.78f) : Colour(0.18f, 0.17f, 0.16f);
  layout.floor_height = house ? 2.8 : 3.0 + 0.6 * pick(v, 6);
  layout.spacing = house ? 3.5 + pick(v, 7) : 2.4 + 1.2 * pick(v, 7);
  layout.width = layout.spacing * (house ? 0.35 : 0.45 + 0.15 * pick(v, 8));
  layout.height = house ? 1.2 : 1.4 + 0.4 * pick(v, 9);
  return layout;
}

/// Facades of city blocks (houses: lower floors, fewer and smaller windows).
Colour facade(const ShadingPoint& p, bool house) {
  const FacadeLayout& layout = facadeLayout(p.variant, house);
  Colour wall = layout.wall;
  if (layout.style == 0) {  // brick
    const double row = std::floor(p.b / 0.075);
    const float mortar = std::max(pulseCoverage(p.b, 0.075, 0.012, p.footprint_b),
                                  pulseCoverage(p.a + (static_cast<long long>(row) % 2 ? 0.125 : 0.0), 0.25, 0.012, p.footprint_a));
    wall = lerp(wall * (0.85f + 0.3f * noise(p, 0.5, 1, 3)), Colour(0.62f, 0.6f, 0.56f), mortar);
  } else {
    wall *= 0.85f + 0.3f * noise(p, 2.0, 1, 5);
    if (layout.style == 2) wall = lerp(wall, Colour(0.35f, 0.35f, 0.35f), pulseCoverage(p.a, 1.5, 0.02, p.footprint_a));
  }
  if (p.extent_a < 2.0f) return wall;
  const double spacing = layout.spacing, width = layout.width, floor_height = layout.floor_height;
  const double frame = 0.08;
  const double start = 0.5 * (p.extent_a - std::floor(p.extent_a / spacing) * spacing + spacing - width);
  const double x = p.a - start, y = p.b - 0.9;
  const float storeys = band(p.b, 0.5, p.extent_b - 1.3, p.footprint_b);
  const float framed = storeys * pulseCoverage(x + frame, spacing, width + 2 * frame, p.footprint_a) *
                       pulseCoverage(y + frame, floor_height, layout.height + 2 * frame, p.footprint_b);
  if (!house) wall = lerp(wall, wall * 0.7f, pulseCoverage(p.b - floor_height + 0.2, floor_height, 0.18, p.footprint_b));
  if (framed <= 0.0f) return wall;
  const float glass = storeys * pulseCoverage(x, spacing, width, p.footprint_a) *
                      pulseCoverage(y, floor_height, layout.height, p.footprint_b);
  if (glass <= 0.0f) return lerp(wall, layout.frame, framed);
  const float reflection = 0.25f * fractalNoise(p.a * 0.4, p.b * 0.8, 1.0, 1, p.footprint, p.variant);
  const Colour glass_colour = Colour(0.10f, 0.12f, 0.15f) + Colour(reflection, reflection, reflection * 1.2f);
  return lerp(lerp(wall, layout.frame, std::max(0.0f, framed - glass)), glass_colour, glass);
}

Colour roof(const ShadingPoint& p) {
  const Colour base = pick(p.variant, 11) < 0.5f ? Colour(0.45f, 0.18f, 0.12f) : Colour(0.22f, 0.22f, 0.24f);
  const float rows = pulseCoverage(p.b, 0.3, 0.05, p.footprint_b);
  return base * (0.9f + 0.25f * noise(p, 1.5, 2, 12)) * (1.0f - 0.4f * rows);
}

Colour carPaint(const ShadingPoint& p) {
  static const Colour kPaint[] = {{0.80f, 0.80f, 0.80f}, {0.55f, 0.56f, 0.58f}, {0.05f, 0.05f, 0.06f},
                                  {0.55f, 0.06f, 0.05f}, {0.08f, 0.16f, 0.45f}, {0.25f, 0.25f, 0.26f},
                                  {0.10f, 0.30f, 0.16f}, {0.70f, 0.60f, 0.20f}};
  const Colour paint = kPaint[static_cast<int>(pick(p.variant, 13) * 8.0f)];
  const float sill = band(p.b, -1.0, 1.18, p.footprint_b);      // dark bumper and sill at the bottom
  const float trim = band(p.b, 0.55, 0.04, p.footprint_b);      // a horizontal crease
  return lerp(paint * (1.0f - 0.3f * trim), Colour(0.06f, 0.06f, 0.06f), sill);
}

Colour signFace(const ShadingPoint& p) {
  static const Colour kFaces[] = {{0.05f, 0.2f, 0.6f}, {0.85f, 0.85f, 0.85f}, {0.8f, 0.65f, 0.05f}, {0.05f, 0.4f, 0.15f}};
  const int type = static_cast<int>(pick(p.variant, 14) * 4.0f);
  const double border = 0.06 + 0.04 * std::min(p.extent_a, p.extent_b);
  const float inside = band(p.a, border, p.extent_a - 2 * border, p.footprint_a) * band(p.b, border, p.extent_b - 2 * border, p.footprint_b);
  const Colour rim = type == 1 ? Colour(0.7f, 0.05f, 0.05f) : Colour(0.9f, 0.9f, 0.9f);
  const float symbol = band(p.b, 0.42 * p.extent_b, 0.16 * p.extent_b, p.footprint_b) *
                       band(p.a, 0.2 * p.extent_a, 0.6 * p.extent_a, p.footprint_a);
  const Colour symbol_colour = type == 1 ? Colour(0.05f, 0.05f, 0.05f) : Colour(0.92f, 0.92f, 0.92f);
  return lerp(lerp(rim, kFaces[type], inside), symbol_colour, symbol * inside);
}

Colour trafficLight(const ShadingPoint& p) {
  const int lit = static_cast<int>(pick(p.variant, 15) * 3.0f);
  static const Colour kLit[] = {{0.95f, 0.15f, 0.08f}, {0.95f, 0.65f, 0.1f}, {0.1f, 0.9f, 0.4f}};
  Colour colour(0.07f, 0.07f, 0.07f);
  const double radius = 0.32 * p.extent_a;
  for (int lamp = 0; lamp < 3; ++lamp) {
    const double du = p.a - 0.5 * p.extent_a, dv = p.b - (0.2 + 0.3 * lamp) * p.extent_b;
    const float cover = std::clamp(static_cast<float>((radius - std::hypot(du, dv)) / std::max(p.footprint, 1e-3) + 0.5), 0.0f, 1.0f);
    colour = lerp(colour, lamp == lit ? kLit[2 - lamp] : Colour(0.15f, 0.15f, 0.13f), cover);
  }
  return colour;
}

Colour foliage(const ShadingPoint& p) {
  const float leaves = fractalNoise(p.a, p.b, 0.6, 4, p.footprint, p.variant * 31u + 16);
  const float clumps = fractalNoise(p.a, p.b, 2.5, 1, p.footprint, p.variant * 31u + 17);
  const Colour base = lerp(Colour(0.10f, 0.26f, 0.05f), Colour(0.22f, 0.32f, 0.08f), pick(p.variant, 18));
  const float light = std::clamp(0.25f + 1.9f * (leaves - 0.35f) + 0.6f * (clumps - 0.5f), 0.12f, 1.6f);
  return base * light;
}

Colour grass(const ShadingPoint& p) {
  const float dry = fractalNoise(p.a, p.b, 14.0, 2, p.footprint, 19);
  const float blades = fractalNoise(p.a, p.b, 0.4, 3, p.footprint, 20);
  return lerp(Colour(0.20f, 0.34f, 0.09f), Colour(0.46f, 0.44f, 0.26f), std::clamp(1.6f * dry - 0.5f, 0.0f, 1.0f)) *
         (0.75f + 0.5f * blades);
}

}  // namespace

Eigen::Vector3f albedo(Material material, const ShadingPoint& p, const RoadProfile& road) {
  switch (material) {
    case Material::kAsphalt: return asphalt(p, road);
    case Material::kSidewalk: return sidewalk(p);
    case Material::kCurb:
      return Colour(0.64f, 0.63f, 0.60f) * (0.85f + 0.3f * noise(p, 0.8, 2, 22)) *
             (1.0f - 0.5f * pulseCoverage(p.a, 1.0, 0.02, p.footprint_a));
    case Material::kFacade: return facade(p, false);
    case Material::kHouseWall: return facade(p, true);
    case Material::kRoof: return roof(p);
    case Material::kCarPaint: return carPaint(p);
    case Material::kCarGlass: {
      const float reflection = 0.2f * noise(p, 1.2, 2, 23);
      return Colour(0.07f + reflection, 0.08f + reflection, 0.10f + reflection);
    }
    case Material::kTyre: return Colour(0.05f, 0.05f, 0.05f) * (0.8f + 0.4f * noise(p, 0.1, 1, 24));
    case Material::kMetal: return Colour(0.46f, 0.47f, 0.48f) * (0.8f + 0.4f * noise(p, 0.7, 2, 25));
    case Material::kSign: return signFace(p);
    case Material::kTrafficLight: return trafficLight(p);
    case Material::kFoliage: return foliage(p);
    case Material::kBark: return Colour(0.26f, 0.19f, 0.12f) * (0.6f + 0.8f * fractalNoise(p.a * 4.0, p.b * 0.5, 0.5, 2, p.footprint * 4.0, 26));
    case Material::kGrass: return grass(p);
    case Material::kGuardRail:
      return Colour(0.62f, 0.63f, 0.65f) * (0.8f + 0.3f * pulseCoverage(p.b, 0.11, 0.055, p.footprint_b)) *
             (0.85f + 0.3f * noise(p, 3.0, 2, 27));
    case Material::kConcrete:
      return Colour(0.56f, 0.55f, 0.52f) * (0.8f + 0.35f * noise(p, 1.5, 3, 28)) *
             (1.0f - 0.5f * pulseCoverage(p.a, 4.0, 0.03, p.footprint_a));
    case Material::kWood:
      return Colour(0.42f, 0.30f, 0.18f) * (0.8f + 0.3f * noise(p, 0.6, 2, 29)) *
             (1.0f - 0.7f * pulseCoverage(p.a, 0.14, 0.025, p.footprint_a));
    case Material::kTruck: {
      static const Colour kBody[] = {{0.85f, 0.85f, 0.84f}, {0.6f, 0.1f, 0.08f}, {0.1f, 0.2f, 0.5f}, {0.4f, 0.42f, 0.4f}};
      const Colour body = kBody[static_cast<int>(pick(p.variant, 30) * 4.0f)];
      const float stripe = band(p.b, 1.2, 0.35, p.footprint_b);
      return lerp(body, Colour(0.9f, 0.55f, 0.05f), stripe * (pick(p.variant, 31) < 0.5f ? 1.0f : 0.0f));
    }
  }
  return Colour(0.5f, 0.5f, 0.5f);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
