// The C ABI from C++, against the CLI: for three meshes (the demo scene and two
// made up here: a knotted tube of quads and a terrain with pillars) every way of
// giving the mesh (a file, its bytes, double and float arrays) and of giving the
// settings (a JSON object, the CLI's whole result file) yields the CLI's JSON byte
// for byte; the tagged primitive structs hold the JSON's numbers exactly; every
// export equals the CLI's `--export` file; errors come back as codes with a
// per-thread message; progress reaches the caller's thread; a flag or the callback
// cancels. tests/run.sh builds this with AddressSanitizer (leaks included).
//
// Usage: abi_test PRIMDECOMP_BIN DEMO_SCENE_OBJ WORK_DIR
#include <primdecomp.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

static int failures = 0;
static int checks = 0;

#define CHECK(cond, ...)                                            \
  do {                                                              \
    checks++;                                                       \
    if (!(cond)) {                                                  \
      failures++;                                                   \
      std::fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond); \
      std::fprintf(stderr, __VA_ARGS__);                            \
      std::fprintf(stderr, "\n");                                   \
    }                                                               \
  } while (0)

static std::string read_file(const std::string &path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

static void write_file(const std::string &path, const std::string &text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

// ---- a small JSON reader (enough for a primdecomp result) ---------------------

struct Json {
  enum Type { Null, Bool, Number, String, Array, Object } type = Null;
  double number = 0;
  bool boolean = false;
  std::string text;
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> fields;

  const Json *get(const std::string &key) const {
    for (auto &f : fields)
      if (f.first == key) return &f.second;
    return nullptr;
  }
};

struct JsonParser {
  const std::string &s;
  size_t i = 0;
  explicit JsonParser(const std::string &text) : s(text) {}

  void ws() {
    while (i < s.size() && std::strchr(" \t\r\n", s[i])) i++;
  }
  std::string str() {
    std::string out;
    i++;  // opening quote
    while (i < s.size() && s[i] != '"') {
      if (s[i] == '\\') i++;  // the tests' strings hold no escapes that matter
      out += s[i++];
    }
    i++;
    return out;
  }
  Json value() {
    ws();
    Json v;
    char c = s[i];
    if (c == '{') {
      v.type = Json::Object;
      i++;
      ws();
      while (s[i] != '}') {
        ws();
        std::string k = str();
        ws();
        i++;  // ':'
        v.fields.emplace_back(k, value());
        ws();
        if (s[i] == ',') i++;
        ws();
      }
      i++;
    } else if (c == '[') {
      v.type = Json::Array;
      i++;
      ws();
      while (s[i] != ']') {
        v.items.push_back(value());
        ws();
        if (s[i] == ',') i++;
        ws();
      }
      i++;
    } else if (c == '"') {
      v.type = Json::String;
      v.text = str();
    } else if (c == 't' || c == 'f') {
      v.type = Json::Bool;
      v.boolean = c == 't';
      i += v.boolean ? 4 : 5;
    } else if (c == 'n') {
      i += 4;
    } else {
      v.type = Json::Number;
      char *end = nullptr;
      v.number = std::strtod(s.c_str() + i, &end);  // correctly rounded, as serde's
      i = end - s.c_str();
    }
    return v;
  }
};

static Json parse_json(const std::string &text) {
  JsonParser p(text);
  return p.value();
}

// ---- meshes -------------------------------------------------------------------

struct Obj {
  std::vector<double> positions;
  std::vector<uint32_t> indices, sizes;
};

// `v` and `f` lines of an OBJ (1-based indices, `a/b/c` corners), as the CLI reads them.
static Obj read_obj(const std::string &path) {
  Obj m;
  std::istringstream in(read_file(path));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string tag;
    l >> tag;
    if (tag == "v") {
      std::string x, y, z;
      l >> x >> y >> z;
      for (auto *c : {&x, &y, &z}) m.positions.push_back(std::strtod(c->c_str(), nullptr));
    } else if (tag == "f") {
      std::string corner;
      uint32_t n = 0;
      while (l >> corner) {
        m.indices.push_back(std::strtoul(corner.c_str(), nullptr, 10) - 1);
        n++;
      }
      m.sizes.push_back(n);
    }
  }
  return m;
}

static void print_v(std::string &out, double x, double y, double z) {
  char b[128];
  std::snprintf(b, sizeof b, "v %.17g %.17g %.17g\n", x, y, z);
  out += b;
}

// A trefoil knot's tube: `rings` rings of `around` vertices, quads between them.
static std::string knot_obj(int rings, int around) {
  const double pi = std::acos(-1.0);
  std::string out = "o knot\n";
  auto curve = [&](double t, double p[3]) {
    p[0] = std::sin(t) + 2 * std::sin(2 * t);
    p[1] = std::cos(t) - 2 * std::cos(2 * t);
    p[2] = -std::sin(3 * t);
  };
  for (int i = 0; i < rings; i++) {
    double t = 2 * pi * i / rings, p[3], q[3];
    curve(t, p);
    curve(t + 1e-4, q);
    double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double &c : d) c /= dl;
    // A frame around the tangent: n = normalize(d x z), b = d x n.
    double n[3] = {d[1], -d[0], 0};
    double nl = std::sqrt(n[0] * n[0] + n[1] * n[1]);
    for (double &c : n) c /= nl;
    double b[3] = {d[1] * n[2] - d[2] * n[1], d[2] * n[0] - d[0] * n[2], d[0] * n[1] - d[1] * n[0]};
    for (int j = 0; j < around; j++) {
      double a = 2 * pi * j / around, r = 0.45;
      print_v(out, p[0] + r * (std::cos(a) * n[0] + std::sin(a) * b[0]),
              p[1] + r * (std::cos(a) * n[1] + std::sin(a) * b[1]),
              p[2] + r * (std::cos(a) * n[2] + std::sin(a) * b[2]));
    }
  }
  for (int i = 0; i < rings; i++)
    for (int j = 0; j < around; j++) {
      int a = i * around + j, b = i * around + (j + 1) % around;
      int c = ((i + 1) % rings) * around + (j + 1) % around, d = ((i + 1) % rings) * around + j;
      out += "f " + std::to_string(a + 1) + " " + std::to_string(b + 1) + " " +
             std::to_string(c + 1) + " " + std::to_string(d + 1) + "\n";
    }
  return out;
}

// A 40 x 40 terrain of triangles (heights on a 1/64 grid: exact in float) with three
// box pillars standing on it.
static std::string terrain_obj() {
  const int n = 40;
  std::string out = "o ground\n";
  auto height = [](int x, int z) {
    unsigned h = (unsigned)(x * 73856093) ^ (unsigned)(z * 19349663);
    double wave = std::floor(32 * (std::sin(0.3 * x) + std::cos(0.2 * z)));
    return (wave + (h % 7)) / 64.0;
  };
  for (int z = 0; z <= n; z++)
    for (int x = 0; x <= n; x++) print_v(out, x * 0.25, height(x, z), z * 0.25);
  for (int z = 0; z < n; z++)
    for (int x = 0; x < n; x++) {
      int a = z * (n + 1) + x + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
      out += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
      out += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
    }
  int first = (n + 1) * (n + 1);
  const double pillars[3][4] = {{2, 2, 0.5, 3}, {6, 3, 0.75, 2}, {4, 8, 0.25, 4.5}};
  for (auto &p : pillars) {
    out += "o pillar\n";
    for (int c = 0; c < 8; c++)
      print_v(out, p[0] + ((c & 1) ? p[2] : -p[2]), (c & 2) ? p[3] : -0.5,
              p[1] + ((c & 4) ? p[2] : -p[2]));
    static const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (auto &q : quads) {
      out += "f";
      for (int k : q) out += " " + std::to_string(first + k + 1);
      out += "\n";
    }
    first += 8;
  }
  return out;
}

// ---- helpers over the API -----------------------------------------------------

static std::string last_error() { return primdecomp_last_error(); }

static std::string json_of(const primdecomp_result *r, size_t level = 0) {
  char *text = nullptr;
  size_t len = 0;
  primdecomp_status s = primdecomp_result_json(r, level, &text, &len);
  CHECK(s == PRIMDECOMP_STATUS_OK, "json: %s", primdecomp_last_error());
  std::string out = text ? std::string(text, len) : std::string();
  CHECK(text == nullptr || std::strlen(text) == len, "json length %zu", len);
  primdecomp_string_free(text);
  return out;
}

static primdecomp_result *run(const primdecomp_mesh *m, const char *settings) {
  primdecomp_result *r = nullptr;
  primdecomp_status s = primdecomp_decompose(m, settings, nullptr, nullptr, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_OK && r, "decompose: status %d: %s", (int)s, primdecomp_last_error());
  return r;
}

/// The JSON of `mesh` (then freed) decomposed with `settings`.
static std::string json_from(primdecomp_mesh *mesh, const char *settings) {
  primdecomp_result *r = run(mesh, settings);
  std::string j = r ? json_of(r) : std::string();
  primdecomp_result_free(r);
  primdecomp_mesh_free(mesh);
  return j;
}

static bool same(const double *a, const Json *j, size_t n) {
  if (!j || j->items.size() != n) return false;
  for (size_t k = 0; k < n; k++)
    if (a[k] != j->items[k].number) return false;
  return true;
}

static bool same(double a, const Json *j) { return j ? a == j->number : a == 0.0; }

/// Each tagged struct holds its JSON entry's numbers exactly.
static void check_structs(const primdecomp_result *r, const Json &doc, const char *what) {
  const primdecomp_primitive *p = nullptr;
  size_t n = 0;
  CHECK(primdecomp_result_primitives(r, 0, &p, &n) == PRIMDECOMP_STATUS_OK, "%s", last_error().c_str());
  const Json *prims = doc.get("primitives");
  CHECK(prims && prims->items.size() == n, "%s: %zu structs", what, n);
  static const char *kinds[6] = {"box", "sphere", "capsule", "cylinder", "frustum", "prism"};
  size_t by_kind[6] = {0};
  for (size_t i = 0; prims && i < n && i < prims->items.size(); i++) {
    const Json &e = prims->items[i];
    const auto &s = p[i].shape;
    bool ok = e.get("kind")->text == kinds[p[i].kind] && e.get("faces")->number == p[i].faces;
    by_kind[p[i].kind]++;
    switch (p[i].kind) {
      case PRIMDECOMP_KIND_BOX:
        ok = ok && same(s.box.center, e.get("center"), 3) && same(s.box.rotation, e.get("rotation"), 4) &&
             same(s.box.half_extents, e.get("half_extents"), 3);
        break;
      case PRIMDECOMP_KIND_SPHERE:
        ok = ok && same(s.sphere.center, e.get("center"), 3) && same(s.sphere.radius, e.get("radius"));
        break;
      case PRIMDECOMP_KIND_CAPSULE:
        ok = ok && same(s.capsule.p0, e.get("p0"), 3) && same(s.capsule.p1, e.get("p1"), 3) &&
             same(s.capsule.radius, e.get("radius"));
        break;
      case PRIMDECOMP_KIND_CYLINDER:
        ok = ok && same(s.cylinder.p0, e.get("p0"), 3) && same(s.cylinder.p1, e.get("p1"), 3) &&
             same(s.cylinder.radius, e.get("radius"));
        break;
      case PRIMDECOMP_KIND_FRUSTUM:
        ok = ok && same(s.frustum.p0, e.get("p0"), 3) && same(s.frustum.p1, e.get("p1"), 3) &&
             same(s.frustum.radius0, e.get("radius0")) && same(s.frustum.radius1, e.get("radius1"));
        break;
      case PRIMDECOMP_KIND_PRISM:
        ok = ok && same(s.prism.center, e.get("center"), 3) && same(s.prism.rotation, e.get("rotation"), 4) &&
             same(s.prism.half_x, e.get("half_x")) && same(s.prism.half_y, e.get("half_y")) &&
             same(s.prism.half_z_top, e.get("half_z_top")) &&
             same(s.prism.half_z_bottom, e.get("half_z_bottom")) && same(s.prism.shift_z, e.get("shift_z"));
        break;
    }
    CHECK(ok, "%s: primitive %zu (%s) differs from its JSON entry", what, i, kinds[p[i].kind]);
  }
  primdecomp_level_info info;
  CHECK(primdecomp_result_level(r, 0, &info) == PRIMDECOMP_STATUS_OK, "level info");
  const Json *stats = doc.get("stats");
  CHECK(info.primitives == n && stats && info.bytes == stats->get("bytes")->number, "%s: level info", what);
  for (int k = 0; k < 6; k++)
    CHECK(info.counts[k] == by_kind[k] && stats->get("counts")->get(kinds[k])->number == by_kind[k],
          "%s: count of %s", what, kinds[k]);
}

// ---- the tests ------------------------------------------------------------------

struct Case {
  std::string name, path;
  std::vector<std::string> cli_flags;
  const char *settings;  // the same run as the flags, as settings JSON
  bool float_exact;      // coordinates exact in float
};

static std::string g_bin, g_work;

static std::string cli(const Case &c, const std::string &out, const std::string &extra = "") {
  std::string cmd = "'" + g_bin + "' decompose '" + c.path + "' -o '" + out + "' --quiet";
  for (auto &f : c.cli_flags) cmd += " " + f;
  cmd += extra;
  int rc = std::system(cmd.c_str());
  CHECK(rc == 0, "CLI failed: %s", cmd.c_str());
  return read_file(out);
}

static void same_as_cli(const Case &c) {
  std::string expect = cli(c, g_work + "/cli_" + c.name + ".json");
  Json doc = parse_json(expect);
  CHECK(doc.get("primitives") && !doc.get("primitives")->items.empty(), "%s: CLI JSON has primitives", c.name.c_str());
  std::printf("  %s: %zu primitives from the CLI (%s)\n", c.name.c_str(),
              doc.get("primitives") ? doc.get("primitives")->items.size() : 0, c.settings ? c.settings : "defaults");

  // 1. From the file.
  primdecomp_mesh *m = nullptr;
  CHECK(primdecomp_mesh_load(c.path.c_str(), &m) == PRIMDECOMP_STATUS_OK, "load: %s", last_error().c_str());
  primdecomp_result *r = run(m, c.settings);
  CHECK(json_of(r) == expect, "%s: JSON from the file differs from the CLI's", c.name.c_str());
  check_structs(r, doc, c.name.c_str());
  primdecomp_result_free(r);

  // 2. The settings as the CLI's whole result file.
  CHECK(json_from(m, expect.c_str()) == expect, "%s: settings from the CLI's file", c.name.c_str());

  // 3. From the bytes in memory.
  std::string bytes = read_file(c.path);
  CHECK(primdecomp_mesh_parse(reinterpret_cast<const uint8_t *>(bytes.data()), bytes.size(), c.path.c_str(), &m) ==
            PRIMDECOMP_STATUS_OK,
        "parse: %s", last_error().c_str());
  CHECK(json_from(m, c.settings) == expect, "%s: JSON from memory differs from the CLI's", c.name.c_str());

  // 4. From double arrays (polygons kept), the path set as the CLI records it.
  Obj o = read_obj(c.path);
  CHECK(primdecomp_mesh_from_doubles(o.positions.data(), o.positions.size() / 3, o.indices.data(), o.indices.size(),
                                     o.sizes.data(), o.sizes.size(), &m) == PRIMDECOMP_STATUS_OK,
        "from_doubles: %s", last_error().c_str());
  CHECK(primdecomp_mesh_face_count(m) == o.sizes.size(), "face count");
  CHECK(primdecomp_mesh_set_path(m, c.path.c_str()) == PRIMDECOMP_STATUS_OK, "set_path");
  CHECK(json_from(m, c.settings) == expect, "%s: JSON from double arrays differs from the CLI's", c.name.c_str());

  // 5. From float arrays, where the coordinates are floats.
  if (c.float_exact) {
    std::vector<float> f(o.positions.begin(), o.positions.end());
    for (size_t k = 0; k < f.size(); k++) CHECK((double)f[k] == o.positions[k], "float-exact coordinate %zu", k);
    CHECK(primdecomp_mesh_from_floats(f.data(), f.size() / 3, o.indices.data(), o.indices.size(), o.sizes.data(),
                                      o.sizes.size(), &m) == PRIMDECOMP_STATUS_OK,
          "from_floats: %s", last_error().c_str());
    primdecomp_mesh_set_path(m, c.path.c_str());
    CHECK(json_from(m, c.settings) == expect, "%s: JSON from float arrays differs from the CLI's", c.name.c_str());
  }
}

/// Every export equals the CLI's `--export` file of the same name; in memory, the
/// single-file formats equal it too (with the model named as the file).
static void exports_as_cli(const Case &c) {
  std::string dir = g_work + "/cli_exports", mine = g_work + "/c_exports";
  std::system(("mkdir -p '" + dir + "' '" + mine + "'").c_str());
  const std::vector<std::string> names = {"scene.glb", "scene.gltf", "scene.usda", "scene.tscn", "scene.urdf", "scene.mjcf"};
  std::string extra;
  for (auto &n : names) extra += " --export '" + dir + "/" + n + "'";
  extra += " --obj '" + dir + "/scene.obj'";
  std::string expect = cli(c, dir + "/scene.json", extra);

  primdecomp_mesh *m = nullptr;
  primdecomp_mesh_load(c.path.c_str(), &m);
  primdecomp_result *r = run(m, c.settings);
  primdecomp_mesh_free(m);
  for (const auto &n : names) {
    primdecomp_status s = primdecomp_result_export(r, 0, (mine + "/" + n).c_str(), nullptr);
    CHECK(s == PRIMDECOMP_STATUS_OK, "export %s: %s", n.c_str(), last_error().c_str());
    CHECK(read_file(mine + "/" + n) == read_file(dir + "/" + n) && !read_file(dir + "/" + n).empty(),
          "export %s differs from the CLI's", n.c_str());
    std::string fmt = n.substr(n.find('.') + 1);
    uint8_t *bytes = nullptr;
    size_t len = 0;
    s = primdecomp_result_export_to_memory(r, 0, fmt.c_str(), "{\"model\": \"scene\"}", &bytes, &len);
    if (fmt == "urdf") {
      // The demo's frustums and prisms need mesh files beside a URDF.
      CHECK(s == PRIMDECOMP_STATUS_INVALID_ARGUMENT && last_error().find("export it to a path") != std::string::npos,
            "urdf in memory: %d %s", (int)s, last_error().c_str());
    } else {
      CHECK(s == PRIMDECOMP_STATUS_OK, "%s in memory: %s", fmt.c_str(), last_error().c_str());
      CHECK(std::string(reinterpret_cast<char *>(bytes), len) == read_file(dir + "/" + n), "%s in memory differs",
            fmt.c_str());
    }
    primdecomp_bytes_free(bytes, len);
  }
  CHECK(primdecomp_result_export(r, 0, (mine + "/scene.obj").c_str(), nullptr) == PRIMDECOMP_STATUS_OK, "obj");
  CHECK(read_file(mine + "/scene.obj") == read_file(dir + "/scene.obj"), "OBJ differs from the CLI's --obj");
  CHECK(primdecomp_result_export(r, 0, (mine + "/scene.json").c_str(), nullptr) == PRIMDECOMP_STATUS_OK, "json");
  CHECK(read_file(mine + "/scene.json") == expect, "exported JSON differs from the CLI's");
  // MuJoCo's .xml needs the format named, as in the CLI.
  CHECK(primdecomp_result_export(r, 0, (mine + "/robot.xml").c_str(), nullptr) == PRIMDECOMP_STATUS_INVALID_ARGUMENT &&
            last_error().find("format") != std::string::npos,
        "xml without a format: %s", last_error().c_str());
  CHECK(primdecomp_result_export(r, 0, (mine + "/robot.xml").c_str(), "{\"format\": \"mjcf\", \"up\": \"z\"}") ==
            PRIMDECOMP_STATUS_OK,
        "mjcf as .xml: %s", last_error().c_str());
  CHECK(read_file(mine + "/robot.xml").find("<mujoco") != std::string::npos, "an MJCF document");
  CHECK(primdecomp_result_export(r, 0, (mine + "/x.glb").c_str(), "{\"upp\": \"z\"}") ==
            PRIMDECOMP_STATUS_INVALID_ARGUMENT &&
            last_error().find("upp") != std::string::npos,
        "unknown option named: %s", last_error().c_str());
  primdecomp_result_free(r);
}

static void errors() {
  primdecomp_mesh *m = nullptr;
  primdecomp_status s = primdecomp_mesh_load("/nonexistent/mesh.obj", &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_INPUT && m == nullptr, "missing file: %d", (int)s);
  CHECK(last_error().find("/nonexistent/mesh.obj") != std::string::npos, "message names the file: %s",
        last_error().c_str());

  const char bad[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n";
  s = primdecomp_mesh_parse(reinterpret_cast<const uint8_t *>(bad), sizeof bad - 1, "bad.obj", &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_INPUT && last_error().find("bad.obj:4") != std::string::npos,
        "malformed OBJ names its line: %s", last_error().c_str());
  s = primdecomp_mesh_parse(reinterpret_cast<const uint8_t *>(bad), sizeof bad - 1, "bad.xyz", &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_INPUT && last_error().find("extension") != std::string::npos,
        "unknown extension: %s", last_error().c_str());

  const double tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t idx[3] = {0, 1, 7};
  s = primdecomp_mesh_from_doubles(tri, 3, idx, 3, nullptr, 0, &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_INPUT && last_error().find("7") != std::string::npos,
        "index out of range: %s", last_error().c_str());
  const uint32_t ok_idx[3] = {0, 1, 2}, sizes[2] = {2, 2};
  s = primdecomp_mesh_from_doubles(tri, 3, ok_idx, 3, sizes, 2, &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_ARGUMENT && last_error().find("face_sizes") != std::string::npos,
        "face sizes that do not add up: %s", last_error().c_str());
  s = primdecomp_mesh_from_doubles(nullptr, 3, ok_idx, 3, nullptr, 0, &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_ARGUMENT && last_error().find("positions") != std::string::npos,
        "NULL positions: %s", last_error().c_str());
  const double nan_tri[9] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
  s = primdecomp_mesh_from_doubles(nan_tri, 3, ok_idx, 3, nullptr, 0, &m);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_INPUT, "NaN coordinate: %d %s", (int)s, last_error().c_str());
  CHECK(primdecomp_mesh_from_doubles(tri, 3, ok_idx, 3, nullptr, 0, nullptr) == PRIMDECOMP_STATUS_INVALID_ARGUMENT,
        "NULL out");

  CHECK(primdecomp_mesh_from_doubles(tri, 3, ok_idx, 3, nullptr, 0, &m) == PRIMDECOMP_STATUS_OK, "one triangle");
  CHECK(last_error().empty(), "a call that succeeds clears the message: %s", last_error().c_str());
  primdecomp_result *r = nullptr;
  s = primdecomp_decompose(m, "{\"targets\": [3], \"rim_wieght\": 1}", nullptr, nullptr, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_SETTINGS && r == nullptr && last_error().find("rim_wieght") != std::string::npos,
        "unknown setting named: %s", last_error().c_str());
  s = primdecomp_decompose(m, "{\"targets\": [0]}", nullptr, nullptr, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_SETTINGS, "zero target: %s", last_error().c_str());
  s = primdecomp_decompose(m, "{not json", nullptr, nullptr, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_SETTINGS, "settings that do not parse: %s", last_error().c_str());
  s = primdecomp_decompose(nullptr, nullptr, nullptr, nullptr, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_INVALID_ARGUMENT && last_error().find("mesh") != std::string::npos, "NULL mesh");

  r = run(m, "{\"targets\": [1]}");
  primdecomp_level_info info;
  CHECK(primdecomp_result_level(r, 1, &info) == PRIMDECOMP_STATUS_OUT_OF_RANGE, "level out of range");
  CHECK(last_error().find("out of range") != std::string::npos, "%s", last_error().c_str());
  char *text = nullptr;
  CHECK(primdecomp_result_json(r, 5, &text, nullptr) == PRIMDECOMP_STATUS_OUT_OF_RANGE && text == nullptr, "json level");
  CHECK(primdecomp_result_level_count(r) == 1 && primdecomp_result_level_count(nullptr) == 0, "level count");

  // The message is per thread: an error on another thread leaves this one's alone.
  std::string other;
  std::thread t([&] {
    primdecomp_mesh *x = nullptr;
    primdecomp_mesh_load("/nonexistent/other.obj", &x);
    other = primdecomp_last_error();
  });
  t.join();
  CHECK(other.find("other.obj") != std::string::npos && last_error().find("out of range") != std::string::npos,
        "per-thread messages: '%s' / '%s'", other.c_str(), last_error().c_str());

  primdecomp_result_free(r);
  primdecomp_mesh_free(m);
  primdecomp_mesh_free(nullptr);
  primdecomp_result_free(nullptr);
  primdecomp_string_free(nullptr);
  primdecomp_bytes_free(nullptr, 0);
}

/// What a level's distance is measured to: the solid for a closed box under
/// "solid", the surface for the same box with one side left open (or without
/// "solid"), nothing for a greedy level; always what the JSON says.
static void measured_to() {
  // A 2 x 1 x 0.5 box, two triangles a side, outward; the open box lacks the last side.
  const double corners[8 * 3] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0, 0, 0, 0.5, 2, 0, 0.5, 2, 1, 0.5, 0, 1, 0.5};
  const uint32_t tris[12 * 3] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  struct Run {
    const char *what;
    size_t faces;
    const char *settings;
    primdecomp_measured_to expect;
    const char *in_json;  // stats.distance.measured_to, or nullptr when absent
  };
  const Run runs[] = {
      {"closed box, solid", 12, "{\"solid\": true}", PRIMDECOMP_MEASURED_TO_SOLID, "solid"},
      {"open box, solid", 10, "{\"solid\": true}", PRIMDECOMP_MEASURED_TO_MESH, nullptr},
      {"closed box, no solid", 12, "{}", PRIMDECOMP_MEASURED_TO_MESH, nullptr},
      {"closed box, greedy", 12, "{\"targets\": [2], \"solid\": true}", PRIMDECOMP_MEASURED_TO_NONE, nullptr},
  };
  for (const Run &c : runs) {
    primdecomp_mesh *m = nullptr;
    CHECK(primdecomp_mesh_from_doubles(corners, 8, tris, c.faces * 3, nullptr, 0, &m) == PRIMDECOMP_STATUS_OK,
          "%s: %s", c.what, last_error().c_str());
    primdecomp_result *r = run(m, c.settings);
    primdecomp_measured_to to = PRIMDECOMP_MEASURED_TO_NONE;
    if (c.expect == PRIMDECOMP_MEASURED_TO_NONE) to = PRIMDECOMP_MEASURED_TO_SOLID;  // must be overwritten
    CHECK(primdecomp_result_level_measured_to(r, 0, &to) == PRIMDECOMP_STATUS_OK, "%s: %s", c.what,
          last_error().c_str());
    CHECK(to == c.expect, "%s: measured to %d, expected %d", c.what, (int)to, (int)c.expect);
    Json doc = parse_json(json_of(r));
    const Json *d = doc.get("stats") ? doc.get("stats")->get("distance") : nullptr;
    const Json *j = d ? d->get("measured_to") : nullptr;
    CHECK((d != nullptr) == (c.expect != PRIMDECOMP_MEASURED_TO_NONE), "%s: stats.distance", c.what);
    CHECK(c.in_json ? j && j->text == c.in_json : j == nullptr, "%s: the JSON's measured_to", c.what);
    primdecomp_level_info info;
    primdecomp_result_level(r, 0, &info);
    std::printf("  %s: %zu primitives, distance %g, measured to %s\n", c.what, info.primitives, info.distance,
                to == PRIMDECOMP_MEASURED_TO_SOLID ? "the solid" : to == PRIMDECOMP_MEASURED_TO_MESH ? "the mesh" : "nothing");
    if (&c == &runs[0]) {
      CHECK(primdecomp_result_level_measured_to(r, 1, &to) == PRIMDECOMP_STATUS_OUT_OF_RANGE, "level out of range");
      CHECK(primdecomp_result_level_measured_to(r, 0, nullptr) == PRIMDECOMP_STATUS_INVALID_ARGUMENT &&
                last_error().find("out") != std::string::npos,
            "NULL out: %s", last_error().c_str());
      CHECK(primdecomp_result_level_measured_to(nullptr, 0, &to) == PRIMDECOMP_STATUS_INVALID_ARGUMENT,
            "NULL result");
    }
    primdecomp_result_free(r);
    primdecomp_mesh_free(m);
  }
}

struct Seen {
  std::thread::id thread;
  bool other_thread = false;
  int calls = 0;
  std::set<std::string> stages;
  std::string last_stage;
  double last_fraction = -1;
  int cancel_in_merge = 0;
  std::atomic<int32_t> *flag = nullptr;
};

static int on_progress(void *user, const char *stage, double fraction) {
  Seen *s = static_cast<Seen *>(user);
  if (std::this_thread::get_id() != s->thread) s->other_thread = true;
  s->calls++;
  s->stages.insert(stage);
  s->last_stage = stage;
  s->last_fraction = fraction;
  if (s->flag) s->flag->store(1);  // as another thread would
  return s->cancel_in_merge && std::string(stage) == "merge";
}

static void progress_and_cancel(const Case &c) {
  primdecomp_mesh *m = nullptr;
  CHECK(primdecomp_mesh_load(c.path.c_str(), &m) == PRIMDECOMP_STATUS_OK, "%s", last_error().c_str());
  // A slow run (exact re-pricing, one part), so that the callback sees it going.
  const char *slow = "{\"targets\": [8], \"reprice\": \"exact\", \"partitions\": 1, \"solid\": true}";

  Seen seen;
  seen.thread = std::this_thread::get_id();
  primdecomp_result *r = nullptr;
  primdecomp_status s = primdecomp_decompose(m, slow, on_progress, &seen, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_OK, "run with progress: %s", last_error().c_str());
  CHECK(!seen.other_thread, "progress is called on the caller's thread");
  CHECK(seen.calls >= 1 && seen.last_stage == "postprocess" && seen.last_fraction == 1.0,
        "the last report is the end: %d calls, %s %g", seen.calls, seen.last_stage.c_str(), seen.last_fraction);
  std::string stages;
  for (auto &st : seen.stages) stages += st + " ";
  std::printf("  progress: %d calls on the calling thread; stages seen: %s\n", seen.calls, stages.c_str());
  primdecomp_result_free(r);

  // The callback cancels when it first sees the merge stage.
  Seen stop;
  stop.thread = std::this_thread::get_id();
  stop.cancel_in_merge = 1;
  r = nullptr;
  s = primdecomp_decompose(m, slow, on_progress, &stop, nullptr, &r);
  CHECK(s == PRIMDECOMP_STATUS_CANCELLED && r == nullptr && stop.last_stage == "merge",
        "the callback cancels: status %d, %s, last stage %s", (int)s, last_error().c_str(), stop.last_stage.c_str());
  primdecomp_result_free(r);

  // A flag set from another thread cancels; one set before the run stops it at once.
  std::atomic<int32_t> flag(1);
  static_assert(sizeof(flag) == sizeof(int32_t), "lock-free int32");
  r = nullptr;
  s = primdecomp_decompose(m, slow, nullptr, nullptr, reinterpret_cast<const int32_t *>(&flag), &r);
  CHECK(s == PRIMDECOMP_STATUS_CANCELLED && r == nullptr && last_error() == "cancelled", "flag set before: %d %s",
        (int)s, last_error().c_str());
  flag.store(0);
  std::thread setter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    flag.store(1);
  });
  s = primdecomp_decompose(m, slow, nullptr, nullptr, reinterpret_cast<const int32_t *>(&flag), &r);
  setter.join();
  CHECK(s == PRIMDECOMP_STATUS_CANCELLED || s == PRIMDECOMP_STATUS_OK, "flag set meanwhile: %d", (int)s);
  std::printf("  a flag set after 30 ms: %s\n", s == PRIMDECOMP_STATUS_CANCELLED ? "cancelled" : "finished first");
  primdecomp_result_free(r);

  // Two threads decompose one mesh at once: the same JSON as one alone.
  std::string a, b;
  std::thread ta([&] {
    primdecomp_result *x = run(m, c.settings);
    a = json_of(x);
    primdecomp_result_free(x);
  });
  std::thread tb([&] {
    primdecomp_result *x = run(m, c.settings);
    b = json_of(x);
    primdecomp_result_free(x);
  });
  ta.join();
  tb.join();
  primdecomp_result *x = run(m, c.settings);
  CHECK(!a.empty() && a == b && a == json_of(x), "concurrent runs on one mesh agree");
  primdecomp_result_free(x);
  primdecomp_mesh_free(m);
}

int main(int argc, char **argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: abi_test PRIMDECOMP_BIN DEMO_SCENE_OBJ WORK_DIR\n");
    return 2;
  }
  g_bin = argv[1];
  g_work = argv[3];
  std::string version = primdecomp_version();
  CHECK(!version.empty() && std::isdigit((unsigned char)version[0]) && version.find('.') != std::string::npos,
        "version: %s", version.c_str());
  std::printf("primdecomp %s (C ABI) against %s\n", version.c_str(), g_bin.c_str());

  write_file(g_work + "/knot.obj", knot_obj(96, 12));
  write_file(g_work + "/knot_fine.obj", knot_obj(480, 24));
  write_file(g_work + "/terrain.obj", terrain_obj());
  std::vector<Case> cases = {
      {"demo_scene", argv[2], {"-n", "150"}, "{\"targets\": [150]}", false},
      {"knot", g_work + "/knot.obj", {"--tolerance", "1%"}, "{\"tolerance\": [{\"diagonal\": 0.01}]}", false},
      {"terrain", g_work + "/terrain.obj", {}, nullptr, true},
  };
  std::printf("the CLI's JSON, byte for byte, from files, memory and arrays:\n");
  for (auto &c : cases) same_as_cli(c);
  std::printf("exports equal the CLI's:\n");
  exports_as_cli(cases[0]);
  std::printf("errors, progress, cancellation, threads:\n");
  errors();
  measured_to();
  // A finer knot (11,520 quads), so that the slow run's progress is seen going.
  progress_and_cancel({"knot_fine", g_work + "/knot_fine.obj", {}, "{\"targets\": [40]}", false});

  std::printf("%d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
