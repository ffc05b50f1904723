// RSML (docs/rsml.md): the reader (tinyxml2, for its line numbers) and the writer (plain text: the same
// document, the same bytes).
#include "rootsim/rsml.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "rootsim/content_hash.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/signature.hpp"

namespace fs = std::filesystem;

namespace rootsim::rsml {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string_view::npos) return {};
  const auto b = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(a, b - a + 1));
}

// a number as XML holds it (surrounding blanks allowed, a leading '+' too); false when the text is
// not exactly one number
bool parseNumber(std::string_view text, double& out) {
  std::string t = trim(text);
  if (!t.empty() && t[0] == '+') t.erase(0, 1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// text from the file in a message: one printable line (control characters as '?'), at most 40 bytes
std::string shown(std::string_view text) {
  std::string o(text.substr(0, 40));
  for (char& c : o)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return text.size() > 40 ? o + "..." : o;
}

// the element's text, "" when it has none
std::string textOf(const tinyxml2::XMLElement* e) {
  const char* t = e->GetText();
  return t ? trim(t) : std::string();
}

// an element's id: `id` (openalea, RootNav, rootsim) or `ID` (SmartRoot, RootSystemTracker)
std::string idOf(const tinyxml2::XMLElement* e) {
  if (const char* id = e->Attribute("id")) return id;
  if (const char* id = e->Attribute("ID")) return id;
  return {};
}

struct Reader {
  std::string name;       // the file, for messages
  double mmPerUnit = 1;
  std::size_t points = 0; // in the whole document (kMaxPoints)
  // the 2D+t dialect: the observation times [h] (index = coord_t), and whether any root had times
  std::vector<double> observations;
  int rootsWithTimes = 0, rootsWithoutTimes = 0;
  int firstRootWithTimesLine = 0, firstRootWithoutTimesLine = 0;

  [[noreturn]] void fail(const tinyxml2::XMLNode* at, const std::string& what) const {
    throw SceneError(name + ":" + std::to_string(at ? at->GetLineNum() : 1) + ": " + what);
  }

  double number(const tinyxml2::XMLElement* at, std::string_view text, const std::string& what) const {
    double v = 0;
    if (!parseNumber(text, v)) fail(at, what + ": expected a number, found \"" + shown(text) + "\"");
    return v;
  }

  std::vector<Property> properties(const tinyxml2::XMLElement* parent) const {
    std::vector<Property> out;
    const tinyxml2::XMLElement* props = parent->FirstChildElement("properties");
    if (!props) return out;
    for (const tinyxml2::XMLElement* p = props->FirstChildElement(); p; p = p->NextSiblingElement()) {
      Property q;
      q.name = p->Name();
      const char* v = p->Attribute("value");
      q.text = v ? trim(v) : textOf(p);
      if (!parseNumber(q.text, q.number)) q.number = NAN;
      out.push_back(std::move(q));
    }
    return out;
  }

  // one coordinate of a point: attribute c (or coord_c), or child element c; false when absent
  bool coordinate(const tinyxml2::XMLElement* pt, const char* c, double& v) const {
    const std::string coordName = std::string("coord_") + c;
    const char* a = pt->Attribute(c);
    if (!a) a = pt->Attribute(coordName.c_str());
    if (a) {
      v = number(pt, a, std::string("point ") + c);
      return true;
    }
    const tinyxml2::XMLElement* e = pt->FirstChildElement(c);
    if (!e) e = pt->FirstChildElement(coordName.c_str());
    if (!e) return false;
    v = number(e, textOf(e), std::string("point ") + c);
    return true;
  }

  double toMm(const tinyxml2::XMLElement* pt, double v, const char* c) const {
    const double mm = v * mmPerUnit;
    if (!std::isfinite(v) || !std::isfinite(mm))
      fail(pt, std::string("point ") + c + " is not finite");
    if (std::fabs(mm) > kMaxCoordMm)
      fail(pt, std::string("point ") + c + " = " + numberText(mm) + " mm is absurd (beyond " +
                   decimalNumber(kMaxCoordMm) + " mm, 1 km: a wrong unit or resolution?)");
    return mm;
  }

  void root(const tinyxml2::XMLElement* e, Plant& plant, int parent, int order) {
    Root r;
    r.line = e->GetLineNum();
    r.parent = parent;
    r.order = order;
    r.id = idOf(e);
    if (const char* label = e->Attribute("label")) r.label = label;
    r.properties = properties(e);
    const tinyxml2::XMLElement* geometry = e->FirstChildElement("geometry");
    const tinyxml2::XMLElement* polyline = geometry ? geometry->FirstChildElement("polyline") : nullptr;
    if (!polyline) fail(e, "<root" + (r.id.empty() ? std::string() : " id=\"" + shown(r.id) + "\"") + "> has no <geometry><polyline>");
    bool allZ = true;
    // RootSystemTracker's per-point attributes: present on the first point means present on every point
    const tinyxml2::XMLElement* first = polyline->FirstChildElement("point");
    const bool timed = first && first->Attribute("coord_t");
    std::vector<Function> perPoint;
    for (const char* a : {"diameter", "vx", "vy"})
      if (first && first->Attribute(a)) perPoint.push_back(Function{a, "polyline", {}, {}});
    const std::string rootName = "root" + (r.id.empty() ? std::string() : " " + shown(r.id));
    for (const tinyxml2::XMLElement* pt = first; pt; pt = pt->NextSiblingElement("point")) {
      double x = 0, y = 0, z = 0;
      if (!coordinate(pt, "x", x)) fail(pt, "<point> without x");
      if (!coordinate(pt, "y", y)) fail(pt, "<point> without y");
      const bool hasZ = coordinate(pt, "z", z);
      allZ = allZ && hasZ;
      r.x.push_back(toMm(pt, x, "x"));
      r.y.push_back(toMm(pt, y, "y"));
      r.z.push_back(hasZ ? toMm(pt, z, "z") : 0.0);
      if (timed) pointTime(pt, rootName, r);
      else if (pt->Attribute("coord_t"))
        fail(pt, "<point> with coord_t where the root's first point has none (RootSystemTracker's 2D+t dialect gives every point coord_t and coord_th)");
      for (Function& f : perPoint) {
        const char* v = pt->Attribute(f.name.c_str());
        if (!v) fail(pt, "<point> without " + f.name + " where the root's first point has one (RootSystemTracker's 2D+t dialect gives it on every point)");
        const double value = number(pt, v, "point " + f.name);
        if (!std::isfinite(value)) fail(pt, "point " + f.name + " is not finite");
        f.samples.push_back(value);
      }
      if (++points > kMaxPoints) fail(pt, "more than " + std::to_string(kMaxPoints) + " points in the file");
    }
    if (r.x.size() < 2)
      fail(polyline, "a root's polyline needs at least two points, found " + std::to_string(r.x.size()));
    if (timed) {
      if (++rootsWithTimes == 1) firstRootWithTimesLine = r.line;
    } else if (++rootsWithoutTimes == 1) {
      firstRootWithoutTimesLine = r.line;
    }
    for (Function& f : perPoint) r.functions.push_back(std::move(f));
    r.hasZ = allZ;
    if (!allZ) std::fill(r.z.begin(), r.z.end(), 0.0);  // some points without z: the polyline is 2D
    if (const tinyxml2::XMLElement* funcs = e->FirstChildElement("functions"))
      for (const tinyxml2::XMLElement* f = funcs->FirstChildElement("function"); f; f = f->NextSiblingElement("function")) {
        Function fn;
        const char* fname = f->Attribute("name");
        if (!fname || !*fname) fail(f, "<function> without a name");
        fn.name = fname;
        if (const char* d = f->Attribute("domain")) fn.domain = d;
        for (const tinyxml2::XMLElement* s = f->FirstChildElement("sample"); s; s = s->NextSiblingElement("sample")) {
          const char* v = s->Attribute("value");
          const double value = number(s, v ? std::string(v) : textOf(s), "function " + shown(fn.name) + " sample");
          if (!std::isfinite(value)) fail(s, "function " + shown(fn.name) + ": a sample is not finite");
          fn.samples.push_back(value);
          if (const char* pos = s->Attribute("position")) fn.positions.push_back(number(s, pos, "function " + shown(fn.name) + " position"));
          if (++points > kMaxPoints) fail(s, "more than " + std::to_string(kMaxPoints) + " samples in the file");
        }
        if (fn.domain == "polyline" && fn.samples.size() != r.x.size())
          fail(f, "function " + shown(fn.name) + " has " + std::to_string(fn.samples.size()) + " samples for the polyline's " +
                      std::to_string(r.x.size()) + " points");
        r.functions.push_back(std::move(fn));
      }
    r.diameterMm = diameterOf(r);
    const int self = static_cast<int>(plant.roots.size());
    plant.roots.push_back(std::move(r));
    for (const tinyxml2::XMLElement* c = e->FirstChildElement("root"); c; c = c->NextSiblingElement("root"))
      root(c, plant, self, order + 1);
  }

  // a point's coord_t and coord_th (the 2D+t dialect): both present, within the observations, never
  // going backwards along the root
  void pointTime(const tinyxml2::XMLElement* pt, const std::string& rootName, Root& r) const {
    const char* t = pt->Attribute("coord_t");
    const char* th = pt->Attribute("coord_th");
    if (!t) fail(pt, "<point> without coord_t where the root's first point has one (RootSystemTracker's 2D+t dialect gives every point coord_t and coord_th)");
    if (!th) fail(pt, "<point> without coord_th (RootSystemTracker's 2D+t dialect gives every point coord_t and coord_th)");
    const double k = number(pt, t, "point coord_t");
    const double h = number(pt, th, "point coord_th");
    if (!std::isfinite(k) || !std::isfinite(h)) fail(pt, "point coord_t or coord_th is not finite");
    if (observations.empty())
      fail(pt, "<point> has coord_t but the metadata has no <observation-hours> (the times of the 2D+t dialect's observations)");
    const double last = static_cast<double>(observations.size() - 1);
    if (k < 0 || k > last + 1e-9)
      fail(pt, "coord_t " + shown(t) + " is outside the observations: expected 0 to " + numberText(last) + " (<observation-hours> gives " +
                   std::to_string(observations.size()) + " observations, the first at " + numberText(observations.front()) + " h)");
    if (!r.timeIndex.empty() && k < r.timeIndex.back() - 1e-9)
      fail(pt, "coord_t goes backwards along " + rootName + ": " + shown(t) + " after " + numberText(r.timeIndex.back()) +
                   " (a root grows at its tip: the times never decrease from its base to its tip)");
    if (!r.timeH.empty() && h < r.timeH.back() - 1e-9)
      fail(pt, "coord_th goes backwards along " + rootName + ": " + shown(th) + " h after " + numberText(r.timeH.back()) +
                   " h (a root grows at its tip: the times never decrease from its base to its tip)");
    r.timeIndex.push_back(k);
    r.timeH.push_back(h);
  }

  // the diameter per point [mm] under its common names (docs/rsml.md, What the reader accepts)
  std::vector<double> diameterOf(const Root& r) const {
    for (const Function& f : r.functions) {
      if (f.domain != "polyline") continue;
      const std::string n = lower(f.name);
      double factor = 0;
      if (n == "diameter" || n == "diameters" || n == "diam" || n == "width" || n == "rootdiameter" ||
          n == "root_diameter")
        factor = 1;
      else if (n == "radius" || n == "radii")
        factor = 2;
      if (factor == 0) continue;
      std::vector<double> d;
      for (double v : f.samples) d.push_back(factor * v * mmPerUnit);
      return d;
    }
    return {};
  }
};

}  // namespace

const Function* Root::function(std::string_view n) const {
  for (const Function& f : functions)
    if (f.name == n) return &f;
  return nullptr;
}

const Property* Root::property(std::string_view n) const {
  for (const Property& p : properties)
    if (p.name == n) return &p;
  return nullptr;
}

const Property* Document::sceneProperty(std::string_view n) const {
  for (const Property& p : sceneProperties)
    if (p.name == n) return &p;
  return nullptr;
}

double mmPerUnit(const std::string& unitText, double resolution) {
  const std::string u = lower(trim(unitText));
  double mm = 0;
  if (u == "mm" || u == "millimeter" || u == "millimetre" || u == "millimeters" || u == "millimetres") mm = 1;
  else if (u == "cm" || u == "centimeter" || u == "centimetre" || u == "centimeters" || u == "centimetres") mm = 10;
  else if (u == "m" || u == "meter" || u == "metre" || u == "meters" || u == "metres") mm = 1000;
  else if (u == "um" || u == "\xc2\xb5m" || u == "\xce\xbcm" || u == "micrometer" || u == "micrometre" ||
           u == "micrometers" || u == "micrometres" || u == "micron" || u == "microns")
    mm = 1e-3;
  else if (u == "nm" || u == "nanometer" || u == "nanometre") mm = 1e-6;
  else if (u == "inch" || u == "in" || u == "inches") mm = 25.4;
  else if (u == "pixel" || u == "pixels" || u == "px") return 1;  // no physical scale: read in pixels
  else return 0;
  // coordinates are pixels; the resolution is pixels per unit (SmartRoot's dpi with unit inch), so
  // a file in the unit itself has resolution 1
  return mm / resolution;
}

std::string pixelSizeUnit(const std::string& unitText) {
  const std::string u = lower(trim(unitText));
  const std::string head = "pixel(";
  if (u.size() > head.size() + 1 && u.compare(0, head.size(), head) == 0 && u.back() == ')')
    return trim(std::string_view(u).substr(head.size(), u.size() - head.size() - 1));
  return {};
}

bool isPixelUnit(const std::string& unitText) {
  const std::string u = lower(trim(unitText));
  return u == "pixel" || u == "pixels" || u == "px";
}

Document parseRsml(const std::string& text, const std::string& name) {
  Reader rd;
  rd.name = name;
  if (text.size() > kMaxFileBytes)
    throw SceneError(name + ":1: larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  tinyxml2::XMLDocument xml;
  if (xml.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    throw SceneError(name + ":" + std::to_string(std::max(xml.ErrorLineNum(), 1)) + ": malformed XML (" +
                     xml.ErrorName() + ")");
  const tinyxml2::XMLElement* top = xml.RootElement();
  if (!top) throw SceneError(name + ":1: no <rsml> element (an empty document)");
  if (std::string(top->Name()) != "rsml")
    rd.fail(top, "the document is a <" + shown(top->Name()) + ">, not an <rsml>");
  Document doc;
  doc.meta.unit = "pixel";   // RSML: without a unit, coordinates are pixels
  doc.meta.version.clear();
  if (const tinyxml2::XMLElement* m = top->FirstChildElement("metadata")) {
    auto text1 = [&](const char* tag) {
      const tinyxml2::XMLElement* e = m->FirstChildElement(tag);
      return e ? textOf(e) : std::string();
    };
    doc.meta.version = text1("version");
    doc.meta.lastModified = text1("last-modified");
    doc.meta.software = text1("software");
    doc.meta.user = text1("user");
    doc.meta.fileKey = text1("file-key");
    if (const tinyxml2::XMLElement* u = m->FirstChildElement("unit")) {
      doc.meta.unit = textOf(u);
      doc.meta.unitLine = u->GetLineNum();
    }
    if (const tinyxml2::XMLElement* res = m->FirstChildElement("resolution")) {
      doc.meta.resolution = rd.number(res, textOf(res), "<resolution>");
      if (!(doc.meta.resolution > 0) || !std::isfinite(doc.meta.resolution))
        rd.fail(res, "<resolution> must be a positive number (pixels per unit), found " + shown(textOf(res)));
    }
    if (const tinyxml2::XMLElement* defs = m->FirstChildElement("property-definitions"))
      for (const tinyxml2::XMLElement* d = defs->FirstChildElement(); d; d = d->NextSiblingElement()) {
        Definition def;
        if (const tinyxml2::XMLElement* e = d->FirstChildElement("label")) def.label = textOf(e);
        if (const tinyxml2::XMLElement* e = d->FirstChildElement("type")) def.type = textOf(e);
        if (const tinyxml2::XMLElement* e = d->FirstChildElement("unit")) def.unit = textOf(e);
        doc.meta.definitions.push_back(std::move(def));
      }
    if (const tinyxml2::XMLElement* ts = m->FirstChildElement("time-sequence")) {
      if (const tinyxml2::XMLElement* e = ts->FirstChildElement("label")) doc.meta.sequenceLabel = textOf(e);
      if (const tinyxml2::XMLElement* e = ts->FirstChildElement("index")) {
        const double idx = rd.number(e, textOf(e), "<time-sequence><index>");
        if (!(idx >= 0 && idx <= 1e9) || idx != std::floor(idx))
          rd.fail(e, "<time-sequence><index> must be a whole number >= 0, found " + shown(textOf(e)));
        doc.meta.sequenceIndex = static_cast<int>(idx);
      }
      if (const tinyxml2::XMLElement* e = ts->FirstChildElement("unified")) {
        const std::string u = lower(textOf(e));
        doc.meta.unified = u == "true" || u == "1";
      }
    }
    if (const tinyxml2::XMLElement* obs = m->FirstChildElement("observation-hours")) {
      const std::string all = textOf(obs);
      std::size_t from = 0;
      while (from <= all.size()) {
        const std::size_t comma = std::min(all.find(',', from), all.size());
        const std::string item = trim(std::string_view(all).substr(from, comma - from));
        if (!item.empty()) {
          const double h = rd.number(obs, item, "<observation-hours>");
          if (!std::isfinite(h)) rd.fail(obs, "<observation-hours>: a time is not finite");
          doc.meta.observationHours.push_back(h);
          if (doc.meta.observationHours.size() > kMaxPoints) rd.fail(obs, "<observation-hours>: too many times");
        }
        from = comma + 1;
      }
    }
    const tinyxml2::XMLElement* unitAt = m->FirstChildElement("unit");
    const tinyxml2::XMLElement* sizeAt = m->FirstChildElement("size");
    if (sizeAt) {
      doc.meta.size = rd.number(sizeAt, textOf(sizeAt), "<size>");
      if (!(doc.meta.size > 0) || !std::isfinite(doc.meta.size))
        rd.fail(sizeAt, "<size> must be a positive number (the pixel size), found " + shown(textOf(sizeAt)));
    }
    if (const std::string sizeUnit = pixelSizeUnit(doc.meta.unit); !sizeUnit.empty()) {
      // RootSystemTracker: pixel coordinates, the pixel's size in <size>, in the unit in brackets
      const double perSizeUnit = mmPerUnit(sizeUnit, 1);
      if (perSizeUnit == 0 || isPixelUnit(sizeUnit))
        rd.fail(unitAt, "unknown unit \"" + shown(sizeUnit) + "\" in <unit>" + shown(doc.meta.unit) +
                            "</unit> (expected pixel(um), pixel(mm), pixel(cm), ...: the unit of <size>)");
      if (!sizeAt)
        rd.fail(unitAt, "<unit>" + shown(doc.meta.unit) + "</unit> needs <size> in the metadata (the pixel size in " + shown(sizeUnit) +
                            ", as RootSystemTracker writes it), found none");
      rd.mmPerUnit = doc.meta.size * perSizeUnit;
      doc.pixelMm = rd.mmPerUnit;
    } else {
      rd.mmPerUnit = mmPerUnit(doc.meta.unit, doc.meta.resolution);
      if (rd.mmPerUnit == 0)
        rd.fail(unitAt ? unitAt : m, "unknown <unit> \"" + shown(doc.meta.unit) +
                                         "\" (expected pixel, px, pixel(um) with <size>, um, micrometer, mm, millimeter, cm, centimeter, m, meter, "
                                         "nm or inch)");
      // a physical unit with a resolution other than 1: the coordinates are pixels of that size
      if (!isPixelUnit(doc.meta.unit) && doc.meta.resolution != 1) doc.pixelMm = rd.mmPerUnit;
    }
    // the 2D+t dialect's observation times: RootSystemTracker lists observations 1..N, observation 0
    // being at 0 h; a list that starts at 0 h lists them all
    if (const tinyxml2::XMLElement* obs = m->FirstChildElement("observation-hours"); obs && !doc.meta.observationHours.empty()) {
      if (doc.meta.observationHours.front() > 0) rd.observations.push_back(0.0);
      for (double h : doc.meta.observationHours) {
        if (!rd.observations.empty() && !(h > rd.observations.back()))
          rd.fail(obs, "<observation-hours> must increase, found " + numberText(h) + " h after " + numberText(rd.observations.back()) + " h");
        rd.observations.push_back(h);
      }
    }
  }
  doc.mmPerUnit = rd.mmPerUnit;
  const tinyxml2::XMLElement* scene = top->FirstChildElement("scene");
  if (!scene) rd.fail(top, "<rsml> has no <scene>");
  doc.sceneProperties = rd.properties(scene);
  if (const Property* t = doc.sceneProperty("time_h"); t && std::isfinite(t->number)) {
    doc.timeH = t->number;
    doc.hasTime = true;
  }
  for (const tinyxml2::XMLElement* p = scene->FirstChildElement("plant"); p; p = p->NextSiblingElement("plant")) {
    Plant plant;
    plant.id = idOf(p);
    if (const char* label = p->Attribute("label")) plant.label = label;
    plant.properties = rd.properties(p);
    for (const tinyxml2::XMLElement* r = p->FirstChildElement("root"); r; r = r->NextSiblingElement("root"))
      rd.root(r, plant, -1, 0);
    doc.plants.push_back(std::move(plant));
  }
  if (rd.rootsWithTimes > 0) {
    // a time-lapse: every root carries its times
    if (rd.rootsWithoutTimes > 0)
      throw SceneError(name + ":" + std::to_string(rd.firstRootWithoutTimesLine) +
                       ": a <root> without coord_t in a 2D+t file (its root at line " + std::to_string(rd.firstRootWithTimesLine) +
                       " has them: every point of every root needs coord_t and coord_th)");
    doc.observationTimesH = rd.observations;
  }
  return doc;
}

Document readRsml(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw SceneError(file.string() + ": not found (an RSML file)");
  if (fs::file_size(file, ec) > kMaxFileBytes)
    throw SceneError(file.string() + ":1: larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file.string() + ": cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parseRsml(text, file.string());
}

// ---- writer ----

namespace {

std::string escape(std::string_view s) {
  std::string o;
  for (char c : s) {
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
      throw SceneError("RSML: a control character cannot be written (XML 1.0)");
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&apos;"; break;
      default: o += c;
    }
  }
  return o;
}

// an element name the writer can use as it is (properties are written as <NAME value=.../>)
void checkName(const std::string& n) {
  bool ok = !n.empty() && (std::isalpha(static_cast<unsigned char>(n[0])) || n[0] == '_') &&
            lower(n.substr(0, 3)) != "xml";
  for (char c : n) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  if (!ok) throw SceneError("RSML: \"" + n + "\" cannot be an XML element name");
}

std::string num(double v) {
  if (!std::isfinite(v)) throw SceneError("RSML: a non-finite number cannot be written (xs:decimal)");
  return decimalNumber(v);
}

void writeProperties(std::ostringstream& o, const std::vector<Property>& props, const std::string& indent) {
  bool any = false;
  for (const Property& p : props) any = any || !std::isnan(p.number) || !p.text.empty();
  if (!any) return;
  o << indent << "<properties>\n";
  for (const Property& p : props) {
    checkName(p.name);
    if (p.text.empty() && std::isnan(p.number)) continue;  // not measured: RSML has no NaN
    const std::string v = p.text.empty() ? num(p.number) : p.text;
    o << indent << "  <" << p.name << " value=\"" << escape(v) << "\"/>\n";
  }
  o << indent << "</properties>\n";
}

void writeRoot(std::ostringstream& o, const Plant& plant, std::size_t i, const std::string& indent) {
  const Root& r = plant.roots[i];
  o << indent << "<root";
  if (!r.id.empty()) o << " id=\"" << escape(r.id) << '"';
  if (!r.label.empty()) o << " label=\"" << escape(r.label) << '"';
  o << ">\n";
  writeProperties(o, r.properties, indent + "  ");
  o << indent << "  <geometry>\n" << indent << "    <polyline>\n";
  for (std::size_t k = 0; k < r.x.size(); ++k) {
    o << indent << "      <point x=\"" << num(r.x[k]) << "\" y=\"" << num(r.y[k]) << '"';
    if (r.hasZ) o << " z=\"" << num(r.z[k]) << '"';
    o << "/>\n";
  }
  o << indent << "    </polyline>\n" << indent << "  </geometry>\n";
  if (!r.functions.empty()) {
    o << indent << "  <functions>\n";
    for (const Function& f : r.functions) {
      o << indent << "    <function name=\"" << escape(f.name) << "\" domain=\"" << escape(f.domain) << "\">\n";
      for (std::size_t k = 0; k < f.samples.size(); ++k) {
        o << indent << "      <sample";
        if (k < f.positions.size()) o << " position=\"" << num(f.positions[k]) << '"';
        o << " value=\"" << num(f.samples[k]) << "\"/>\n";
      }
      o << indent << "    </function>\n";
    }
    o << indent << "  </functions>\n";
  }
  for (std::size_t c = i + 1; c < plant.roots.size(); ++c)
    if (plant.roots[c].parent == static_cast<int>(i)) writeRoot(o, plant, c, indent + "  ");
  o << indent << "</root>\n";
}

}  // namespace

std::string writeRsml(const Document& doc) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  if (!doc.comment.empty()) {
    if (doc.comment.find("--") != std::string::npos) throw SceneError("RSML: a comment cannot hold \"--\"");
    o << "<!-- " << doc.comment << " -->\n";
  }
  const Metadata& m = doc.meta;
  o << "<rsml xmlns:po=\"http://www.plantontology.org/xml-dtd/po.dtd\">\n"
    << "  <metadata>\n"
    << "    <version>" << escape(m.version) << "</version>\n"
    << "    <unit>mm</unit>\n"
    << "    <resolution>1</resolution>\n"
    << "    <last-modified>" << escape(m.lastModified) << "</last-modified>\n"
    << "    <software>" << escape(m.software) << "</software>\n"
    << "    <user>" << escape(m.user) << "</user>\n"
    << "    <file-key>" << escape(m.fileKey) << "</file-key>\n";
  if (!m.definitions.empty()) {
    o << "    <property-definitions>\n";
    for (const Definition& d : m.definitions) {
      o << "      <property-definition>\n"
        << "        <label>" << escape(d.label) << "</label>\n"
        << "        <type>" << escape(d.type) << "</type>\n";
      if (!d.unit.empty()) o << "        <unit>" << escape(d.unit) << "</unit>\n";
      o << "      </property-definition>\n";
    }
    o << "    </property-definitions>\n";
  }
  if (m.sequenceIndex >= 0)
    o << "    <time-sequence>\n"
      << "      <label>" << escape(m.sequenceLabel) << "</label>\n"
      << "      <index>" << m.sequenceIndex << "</index>\n"
      << "      <unified>" << (m.unified ? "true" : "false") << "</unified>\n"
      << "    </time-sequence>\n";
  o << "  </metadata>\n  <scene>\n";
  writeProperties(o, doc.sceneProperties, "    ");
  for (const Plant& p : doc.plants) {
    o << "    <plant";
    if (!p.id.empty()) o << " id=\"" << escape(p.id) << '"';
    if (!p.label.empty()) o << " label=\"" << escape(p.label) << '"';
    o << ">\n";
    writeProperties(o, p.properties, "      ");
    for (std::size_t i = 0; i < p.roots.size(); ++i)
      if (p.roots[i].parent < 0) writeRoot(o, p, i, "      ");
    o << "    </plant>\n";
  }
  o << "  </scene>\n</rsml>\n";
  // rootsim's signature on line 2 carries the SHA-256 of every byte after it: the write rule
  // (write_rule.hpp) replaces the file only while it is as written
  std::string text = o.str();
  const std::string sig = std::string("<!-- ") + outputSignatureText();
  const auto l1 = text.find('\n');
  if (text.compare(l1 + 1, sig.size(), sig) == 0) {
    const auto l2 = text.find('\n', l1 + 1);
    text.insert(l1 + 1 + sig.size(), " sha256:" + sha256Hex(std::string_view(text).substr(l2 + 1)));
  }
  return text;
}

}  // namespace rootsim::rsml
