#include "export/report_html.hpp"

#include <cmath>
#include <cstdint>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/units.hpp"

namespace fibermold {

namespace {

std::string base64(const void* data, std::size_t size)
{
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::uint32_t n =
        (bytes[i] << 16) | (i + 1 < size ? bytes[i + 1] << 8 : 0) | (i + 2 < size ? bytes[i + 2] : 0);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < size ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < size ? digits[n & 63] : '=';
  }
  return out;
}

/// Positions (mm, float32) and triangle indices (uint32), base64.
nlohmann::json mesh_json(const ReportMesh& m)
{
  std::vector<float> positions;
  for (Eigen::Index i = 0; i < m.mesh.num_vertices(); ++i)
    for (int k = 0; k < 3; ++k)
      positions.push_back(static_cast<float>((m.mesh.vertices(i, k) + m.offset[k]) / units::mm));
  std::vector<std::uint32_t> indices;
  for (Eigen::Index f = 0; f < m.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(m.mesh.faces(f, k)));
  return {{"name", m.name},
          {"colour", m.colour},
          {"visible", m.visible},
          {"positions", base64(positions.data(), positions.size() * sizeof(float))},
          {"indices", base64(indices.data(), indices.size() * sizeof(std::uint32_t))}};
}

nlohmann::json line_json(const ReportLine& l)
{
  std::vector<float> points;
  for (const Eigen::Vector3d& p : l.points)
    for (int k = 0; k < 3; ++k) points.push_back(static_cast<float>(p[k] / units::mm));
  return {{"name", l.name},
          {"colour", l.colour},
          {"visible", l.visible},
          {"points", base64(points.data(), points.size() * sizeof(float))}};
}

std::string escaped(const std::string& text)
{
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

std::string table_html(const ReportTable& t)
{
  std::string out = "<h2>" + escaped(t.title) + "</h2>\n<table>\n<tr>";
  for (const std::string& h : t.header) out += "<th>" + escaped(h) + "</th>";
  out += "</tr>\n";
  for (const auto& row : t.rows) {
    out += "<tr>";
    for (const std::string& cell : row) out += "<td>" + escaped(cell) + "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

/// An SVG line plot, 640 × 300 px, with about five ticks per axis at round values (nice_ticks; a log axis
/// at five even steps of its exponent) and a legend.
std::string plot_svg(const ReportPlot& p)
{
  const std::array<std::string, 6> palette{"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"};
  const auto y_of = [&](double y) { return p.log_y ? std::log10(y) : y; };
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (const auto& [name, points] : p.series)
    for (const Eigen::Vector2d& q : points)
      if (std::isfinite(q.y()) && (!p.log_y || q.y() > 0)) {
        x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
        y0 = std::min(y0, y_of(q.y())), y1 = std::max(y1, y_of(q.y()));
      }
  if (!(x1 >= x0) || !(y1 >= y0)) return {};
  if (x1 == x0) x1 = x0 + 1;
  if (y1 == y0) y1 = y0 + 1;
  const double W = 640, H = 300, L = 70, R = 20, T = 20, B = 45;
  const auto px = [&](double x) { return L + (x - x0) / (x1 - x0) * (W - L - R); };
  const auto py = [&](double y) { return H - B - (y_of(y) - y0) / (y1 - y0) * (H - B - T); };
  std::string svg =
      fmt::format("<h2>{}</h2>\n<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\">",
                  escaped(p.title), W, H);
  svg += fmt::format("<path d=\"M{0} {1}V{2}H{3}\" fill=\"none\" stroke=\"#444\"/>", L, T, H - B, W - R);
  for (const double x : nice_ticks(x0, x1, 4, p.whole_x ? 1 : 0))
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" font-size=\"11\" text-anchor=\"middle\">{:.4g}</text>", px(x),
                       H - B + 15, x);
  std::vector<double> ys;
  if (p.log_y)
    for (int k = 0; k <= 4; ++k) ys.push_back(y0 + (y1 - y0) * k / 4);
  else
    ys = nice_ticks(y0, y1);
  for (const double y : ys)
    svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" font-size=\"11\" text-anchor=\"end\">{:.3g}</text>", L - 5,
                       H - B - (y - y0) / (y1 - y0) * (H - B - T) + 4, p.log_y ? std::pow(10, y) : y);
  svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"12\" text-anchor=\"middle\">{}</text>", (L + W - R) / 2,
                     H - 8, escaped(p.x_label));
  svg += fmt::format(
      "<text x=\"14\" y=\"{0}\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 14 {0})\">{1}</text>",
      (H - B + T) / 2, escaped(p.y_label + (p.log_y ? " (log)" : "")));
  for (std::size_t s = 0; s < p.series.size(); ++s) {
    std::string points;
    for (const Eigen::Vector2d& q : p.series[s].second)
      if (std::isfinite(q.y()) && (!p.log_y || q.y() > 0))
        points += fmt::format("{:.1f},{:.1f} ", px(q.x()), py(q.y()));
    const std::string& colour = palette[s % palette.size()];
    svg += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" points=\"{}\"/>", colour, points);
    svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\" fill=\"{}\" text-anchor=\"end\">{}</text>", W - R,
                       T + 12 * (s + 1), colour, escaped(p.series[s].first));
  }
  return svg + "</svg>\n";
}

// The viewer: WebGL 1, flat-shaded triangles and unlit lines, orbit by dragging, zoom by wheel.
constexpr const char* kViewer = R"JS(
(function () {
  const status = document.getElementById('status');
  const canvas = document.getElementById('view');
  const gl = canvas.getContext('webgl', {antialias: true, preserveDrawingBuffer: true});
  if (!gl) { status.textContent = 'WebGL is not available in this browser: no 3D view'; return; }
  const decode = (text, Type) => { const s = atob(text), b = new Uint8Array(s.length);
    for (let i = 0; i < s.length; ++i) b[i] = s.charCodeAt(i); return new Type(b.buffer); };
  const shader = (type, source) => {
    const s = gl.createShader(type); gl.shaderSource(s, source); gl.compileShader(s); return s; };
  const program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER,
    'attribute vec3 p; attribute vec3 n; uniform mat4 m; varying vec3 vn;' +
    'void main() { vn = n; gl_Position = m * vec4(p, 1.0); }'));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER,
    'precision highp float; varying vec3 vn; uniform vec3 c; uniform float lit;' +
    'void main() { float d = lit > 0.5 ? abs(dot(normalize(vn), vec3(0.35, -0.44, 0.83))) : 1.0;' +
    'gl_FragColor = vec4(c * mix(1.0, 0.35 + 0.65 * d, lit), 1.0); }'));
  gl.linkProgram(program);
  gl.useProgram(program);
  const loc = {p: gl.getAttribLocation(program, 'p'), n: gl.getAttribLocation(program, 'n'),
               m: gl.getUniformLocation(program, 'm'), c: gl.getUniformLocation(program, 'c'),
               lit: gl.getUniformLocation(program, 'lit')};
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  const grow = (x, y, z) => { const v = [x, y, z];
    for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], v[k]); hi[k] = Math.max(hi[k], v[k]); } };
  const items = [];
  let triangles = 0;
  for (const mesh of SCENE.meshes) {
    const p = decode(mesh.positions, Float32Array), f = decode(mesh.indices, Uint32Array);
    const data = new Float32Array(f.length * 6);
    for (let t = 0; t < f.length; t += 3) {
      const a = f[t] * 3, b = f[t + 1] * 3, c = f[t + 2] * 3;
      const u = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
      const w = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
      const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
      const nl = Math.hypot(...n) || 1;
      n.forEach((v, k) => n[k] = v / nl);
      [a, b, c].forEach((v, k) => { data.set([p[v], p[v + 1], p[v + 2], n[0], n[1], n[2]], (t + k) * 6);
        if (mesh.visible) grow(p[v], p[v + 1], p[v + 2]); });
    }
    triangles += f.length / 3;
    items.push({name: mesh.name, colour: mesh.colour, visible: mesh.visible, data: data, mode: gl.TRIANGLES,
                count: f.length, lit: 1});
  }
  for (const line of SCENE.lines) {
    const p = decode(line.points, Float32Array), data = new Float32Array(p.length * 2);
    for (let i = 0; i < p.length / 3; ++i) data.set([p[3 * i], p[3 * i + 1], p[3 * i + 2], 0, 0, 0], 6 * i);
    items.push({name: line.name, colour: line.colour, visible: line.visible, data: data, mode: gl.LINE_STRIP,
                count: p.length / 3, lit: 0});
  }
  for (const item of items) {
    item.buffer = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, item.buffer);
    gl.bufferData(gl.ARRAY_BUFFER, item.data, gl.STATIC_DRAW);
  }
  const centre = [0, 1, 2].map(k => (lo[k] + hi[k]) / 2), size = Math.max(1, ...[0, 1, 2].map(k => hi[k] - lo[k]));
  let yaw = -0.6, pitch = 0.5, distance = 1.8 * size, painted = null;
  const multiply = (a, b) => { const r = new Float32Array(16);
    for (let i = 0; i < 4; ++i) for (let j = 0; j < 4; ++j) {
      let s = 0; for (let k = 0; k < 4; ++k) s += a[k * 4 + j] * b[i * 4 + k]; r[i * 4 + j] = s; }
    return r; };
  function draw() {
    canvas.width = canvas.clientWidth; canvas.height = canvas.clientHeight;
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(1, 1, 1, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT); gl.enable(gl.DEPTH_TEST);
    const eye = [centre[0] + distance * Math.cos(pitch) * Math.cos(yaw),
                 centre[1] + distance * Math.cos(pitch) * Math.sin(yaw), centre[2] + distance * Math.sin(pitch)];
    const f = [0, 1, 2].map(k => centre[k] - eye[k]), fl = Math.hypot(...f); f.forEach((v, k) => f[k] = v / fl);
    const s = [f[1], -f[0], 0], sl = Math.hypot(...s) || 1; s.forEach((v, k) => s[k] = v / sl);
    const u = [s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const view = new Float32Array([s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                                   -dot(s, eye), -dot(u, eye), dot(f, eye), 1]);
    const near = distance / 100, far = distance * 10, t = 1 / Math.tan(0.4);
    const aspect = canvas.width / Math.max(1, canvas.height);
    const projection = new Float32Array([t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1,
                                         0, 0, 2 * far * near / (near - far), 0]);
    gl.uniformMatrix4fv(loc.m, false, multiply(projection, view));
    let drawn = 0;
    for (const item of items) {
      if (!item.visible) continue;
      if (item.mode === gl.TRIANGLES) drawn += item.count / 3;
      gl.bindBuffer(gl.ARRAY_BUFFER, item.buffer);
      gl.enableVertexAttribArray(loc.p); gl.vertexAttribPointer(loc.p, 3, gl.FLOAT, false, 24, 0);
      gl.enableVertexAttribArray(loc.n); gl.vertexAttribPointer(loc.n, 3, gl.FLOAT, false, 24, 12);
      gl.uniform3fv(loc.c, item.colour); gl.uniform1f(loc.lit, item.lit);
      gl.drawArrays(item.mode, 0, item.count);
    }
    const error = gl.getError();
    if (error !== gl.NO_ERROR) { status.textContent = 'WebGL error ' + error; return; }
    if (painted === null) {  // once: how much of the view the scene covers
      const pixels = new Uint8Array(canvas.width * canvas.height * 4);
      gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      painted = 0;
      for (let i = 0; i < pixels.length; i += 4)
        if (pixels[i] < 250 || pixels[i + 1] < 250 || pixels[i + 2] < 250) ++painted;
    }
    status.textContent = 'drawn ' + drawn + ' of ' + triangles + ' triangles, ' + painted + ' of ' +
                         canvas.width * canvas.height + ' pixels painted';
  }
  const list = document.getElementById('items');
  for (const item of items) {
    const label = document.createElement('label'), box = document.createElement('input');
    box.type = 'checkbox'; box.checked = item.visible; box.onchange = () => { item.visible = box.checked; draw(); };
    // The legend: the item's colour, a square for a surface, a dash for a line.
    const swatch = document.createElement('span');
    swatch.className = item.mode === gl.TRIANGLES ? 'swatch surface' : 'swatch line';
    swatch.style.background = 'rgb(' + item.colour.map(c => Math.round(255 * c)).join(',') + ')';
    label.appendChild(box); label.appendChild(swatch); label.appendChild(document.createTextNode(item.name + ' '));
    list.appendChild(label);
  }
  let drag = null;
  canvas.onmousedown = e => { drag = [e.clientX, e.clientY]; };
  window.onmouseup = () => { drag = null; };
  window.onmousemove = e => { if (!drag) return; yaw -= (e.clientX - drag[0]) * 0.01;
    pitch = Math.max(-1.5, Math.min(1.5, pitch + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY]; draw(); };
  canvas.onwheel = e => { e.preventDefault(); distance *= Math.exp(e.deltaY * 0.001); draw(); };
  window.onresize = draw;
  draw();
})();
)JS";

} // namespace

std::vector<double> nice_ticks(double lo, double hi, int count, double least_step)
{
  std::vector<double> out;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || count < 1) return {lo};
  const double rough = (hi - lo) / count, power = std::pow(10, std::floor(std::log10(rough)));
  const double unit = rough / power;
  const double step = std::max(least_step, (unit < 1.5 ? 1 : unit < 3 ? 2 : unit < 7 ? 5 : 10) * power); // rounded
  // From the first multiple of step at or above lo, with a little room for rounding at either end.
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; ++k) out.push_back(k * step + 0.0);
  return out;
}

std::string report_html(const std::string& title, const std::vector<ReportMesh>& meshes,
                        const std::vector<ReportLine>& lines, const std::vector<ReportTable>& tables,
                        const std::vector<ReportPlot>& plots, const std::vector<std::string>& warnings)
{
  nlohmann::json scene{{"meshes", nlohmann::json::array()}, {"lines", nlohmann::json::array()}};
  for (const ReportMesh& m : meshes) scene["meshes"].push_back(mesh_json(m));
  for (const ReportLine& l : lines) scene["lines"].push_back(line_json(l));
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escaped(title) + "</title>\n";
  html += "<style>body{font-family:sans-serif;margin:1.5em;max-width:70em}#view{width:100%;height:32em;border:1px "
          "solid #ccc}"
          "table{border-collapse:collapse;margin-bottom:1em}td,th{border:1px solid #ccc;padding:0.2em "
          "0.6em;text-align:left}"
          "#items{display:flex;flex-wrap:wrap;gap:0.3em 1em}#items label{white-space:nowrap}#status{color:#666}"
          ".swatch{display:inline-block;width:1.1em;margin:0 0.3em;vertical-align:middle}.swatch.surface{height:0.8em}"
          ".swatch.line{height:0.2em}"
          "#warnings{background:#fff3cd;border:1px solid #e0b400;padding:0.4em "
          "1em;margin-bottom:1em}</style>\n</head>\n<body>\n";
  html += "<h1>" + escaped(title) + "</h1>\n";
  if (!warnings.empty()) {
    html += "<div id=\"warnings\"><strong>Warnings</strong>\n<ul>\n";
    for (const std::string& w : warnings) html += "<li>" + escaped(w) + "</li>\n";
    html += "</ul>\n</div>\n";
  }
  html += "<canvas id=\"view\"></canvas>\n<p id=\"items\"></p>\n<p id=\"status\">loading</p>\n";
  html += "<p>Drag to turn, scroll to zoom; lengths in mm.</p>\n";
  for (const ReportTable& t : tables) html += table_html(t);
  for (const ReportPlot& p : plots) html += plot_svg(p);
  // No "<" inside the script element ("</script>", "<!--" would end or confuse it): JSON's \u003c.
  std::string data;
  for (char c : scene.dump()) data += c == '<' ? std::string("\\u003c") : std::string(1, c);
  html += "<script>\nconst SCENE = " + data + ";\n" + kViewer + "</script>\n</body>\n</html>\n";
  return html;
}

} // namespace fibermold
