#pragma once
// RSML, the Root System Markup Language (docs/rsml.md): the data model of a root system as an RSML file
// holds it, the reader (any RSML 1.0 file: SmartRoot, RootNav 2.0, CPlantBox, openalea, rootsim) and
// the writer (rootsim export --rsml). Lengths in the model are millimetres, whatever the file's unit.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rootsim::rsml {

// a name with a value, as a <properties> child holds it (<length value="3.2"/> or <length>3.2</length>)
struct Property {
  std::string name;
  std::string text;    // the value as written
  double number = 0;   // the value as a number; NaN when the text is not one
};

// per-node samples of one quantity along a root's polyline (<function name= domain=>)
struct Function {
  std::string name;
  std::string domain = "polyline";   // "polyline" (one sample per point), "uniform" or "length"
  std::vector<double> samples;       // as written (not converted: a diameter in the file's unit per pixel
                                     // stays so; see Document::mmPerUnit), except diameters: see Root
  std::vector<double> positions;     // the "length" domain's sample positions, else empty
};

// a root: its polyline and what is attached to it. Roots are kept flat, in document order (a parent
// before its laterals); nesting is the parent index.
struct Root {
  std::string id, label;
  int parent = -1;                     // index in Plant::roots of the root it branches from; -1: a base root
  int order = 0;                       // 0 base root, 1 its laterals, ...
  std::vector<double> x, y, z;         // the polyline [mm] (z all 0 when the file has none)
  bool hasZ = false;                   // every point had a z
  std::vector<Function> functions;
  std::vector<Property> properties;
  // the diameter along the root [mm], one value per point, from the first function named diameter,
  // diameters, diam, width or root_diameter (any case), or radius / radii (doubled); empty when none
  std::vector<double> diameterMm;
  // RootSystemTracker's 2D+t dialect: per point, coord_t (the observation index at which the root
  // reached the point, fractional between observations) and coord_th (the same in hours); empty when
  // the file has no times. Never decreasing along a root, within [0, the last observation].
  std::vector<double> timeIndex, timeH;
  int line = 0;                        // line of the <root> element in the file
  std::size_t points() const { return x.size(); }
  const Function* function(std::string_view name) const;
  const Property* property(std::string_view name) const;
};

struct Plant {
  std::string id, label;
  std::vector<Property> properties;
  std::vector<Root> roots;
};

// a property-definition of the metadata: a label, a type (real, integer, boolean, string) and a unit
struct Definition {
  std::string label, type, unit;
};

struct Metadata {
  std::string version = "1";
  std::string unit = "mm";            // as written ("pixel", "cm", "micrometer", ...)
  double resolution = 1;              // as written
  std::string lastModified, software, user, fileKey;
  std::vector<Definition> definitions;
  // <time-sequence>: label, index (-1: none), unified
  std::string sequenceLabel;
  int sequenceIndex = -1;
  bool unified = false;
  // <observation-hours>: the times of the observations a file of several holds [h] (openalea,
  // RootSystemTracker: comma-separated); empty when absent
  std::vector<double> observationHours;
  // <size>: RootSystemTracker's pixel size, in the unit inside <unit>pixel(UNIT)</unit>; 0 when absent
  double size = 0;
  int unitLine = 0;                   // the line of <unit> (0: none; RSML's default, pixels)
};

struct Document {
  Metadata meta;
  std::vector<Property> sceneProperties;   // <scene><properties>: a rootsim run's resolved scene keys
  std::vector<Plant> plants;
  double mmPerUnit = 1;                     // file coordinates x mmPerUnit = mm (docs/rsml.md, Units)
  double pixelMm = 0;                       // a pixel's size [mm] where the coordinates are pixels of a
                                            // known size (a resolution, a <size>); 0 otherwise
  // the times of the observations of a 2D+t file [h]: observation k (a point's coord_t) at
  // observationTimesH[k]; observation 0 at 0 h when <observation-hours> starts after 0 (as
  // RootSystemTracker writes it: the hours of observations 1..N). Empty when no point has a coord_t.
  std::vector<double> observationTimesH;
  bool timeLapse() const { return !observationTimesH.empty(); }
  std::string comment;                      // written before <rsml> as an XML comment (the signature)
  double timeH = 0;                         // the growth time the file shows [h]: rootsim's scene property
  bool hasTime = false;                     // time_h (the reader sets both; the writer writes the property)
  const Property* sceneProperty(std::string_view name) const;
};

// the reader's bounds: a coordinate beyond 1e6 mm (1 km) in mm, once converted, is refused as absurd
// (a misread unit or a corrupt file; the largest root systems measured are metres across), and so is a
// file of more than 256 MiB, or more than 1e7 points (the reader holds them all)
inline constexpr double kMaxCoordMm = 1e6;
inline constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;
inline constexpr std::size_t kMaxPoints = 10'000'000;

// millimetres per file unit of a <unit> and <resolution> (docs/rsml.md, Units): mm, cm, m, um (µm),
// with their long names, and pixel (px): pixel coordinates with the resolution in pixels per unit
// is not said by the unit alone, so a pixel file is read in pixels (1 pixel = 1 "mm", flagged by
// Document::meta.unit). Returns 0 for an unknown unit. RootSystemTracker's pixel(UNIT) is not a unit
// here: its scale is <size> (see pixelSizeUnit).
double mmPerUnit(const std::string& unit, double resolution);
// the UNIT of RootSystemTracker's "pixel(UNIT)" (the unit of the pixel size in <size>), "" for any other unit
std::string pixelSizeUnit(const std::string& unit);
// whether a unit says pixels without a scale (pixel, pixels, px, any case)
bool isPixelUnit(const std::string& unit);

// reads an RSML file into millimetres. Plants and roots take their id from `id` (openalea, RootNav,
// rootsim) or `ID` (SmartRoot, RootSystemTracker). Throws SceneError "FILE:LINE: what" for malformed
// XML, no <rsml>, a root without a polyline or with fewer than two points, a non-finite or absurd
// coordinate (beyond kMaxCoordMm), an unknown unit, a polyline-domain function whose length differs
// from the point count, and in the 2D+t dialect: pixel(UNIT) without a positive <size>, a point without
// coord_t or coord_th where others have them, times without <observation-hours>, a coord_t beyond the
// last observation or below 0, a time going backwards along a root, observation hours not increasing
Document readRsml(const std::filesystem::path& file);
// the same from text; `name` stands for the file in messages
Document parseRsml(const std::string& text, const std::string& name);

// the file's text: coordinates and samples in the document's own unit (rootsim writes mm, resolution
// 1), numbers as the shortest decimal text that reads back to the same double (no exponent: RSML's
// schema types them xs:decimal). Properties whose number is NaN are left out (RSML has no NaN).
std::string writeRsml(const Document& doc);

}  // namespace rootsim::rsml
