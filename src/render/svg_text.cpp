#include "svg_text.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace softdrop::detail {
namespace {

const cairo_user_data_key_t kCollector{};

std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

void collect_svg_text(cairo_t* cr, std::vector<SvgText>* texts) {
  cairo_set_user_data(cr, &kCollector, texts, nullptr);
}

void show_text(cairo_t* cr, const std::string& text) {
  auto* texts = static_cast<std::vector<SvgText>*>(cairo_get_user_data(cr, &kCollector));
  if (texts == nullptr) {
    cairo_show_text(cr, text.c_str());
    return;
  }
  SvgText t;
  t.text = text;
  cairo_get_current_point(cr, &t.x, &t.y);
  cairo_user_to_device(cr, &t.x, &t.y);
  cairo_matrix_t font;
  cairo_get_font_matrix(cr, &font);
  double dx = font.xx, dy = font.yx;  // the font's em, along the baseline, on the page
  cairo_user_to_device_distance(cr, &dx, &dy);
  t.size = std::hypot(dx, dy);
  t.angle = std::atan2(dy, dx) * 180 / M_PI;
  cairo_pattern_get_rgba(cairo_get_source(cr), &t.r, &t.g, &t.b, &t.a);  // non-solid sources: black
  t.bold = cairo_toy_font_face_get_weight(cairo_get_font_face(cr)) == CAIRO_FONT_WEIGHT_BOLD;
  texts->push_back(std::move(t));
}

void show_text_with_halo(cairo_t* cr, const std::string& text, double r, double g, double b, double width) {
  auto* texts = static_cast<std::vector<SvgText>*>(cairo_get_user_data(cr, &kCollector));
  if (texts != nullptr) {
    show_text(cr, text);
    SvgText& t = texts->back();
    double w = width, unused = 0;
    cairo_user_to_device_distance(cr, &w, &unused);
    t.halo = std::abs(w), t.hr = r, t.hg = g, t.hb = b;
    return;
  }
  double x = 0, y = 0;
  cairo_get_current_point(cr, &x, &y);
  cairo_save(cr);
  cairo_text_path(cr, text.c_str());
  cairo_set_source_rgb(cr, r, g, b);
  cairo_set_line_width(cr, width);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_stroke(cr);
  cairo_restore(cr);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, text.c_str());
}

void insert_svg_text(const std::string& path, const std::vector<SvgText>& texts) {
  if (texts.empty()) return;
  std::string svg;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read '" + path + "'");
    svg.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto end = svg.rfind("</svg>");
  if (end == std::string::npos) throw std::runtime_error("'" + path + "': no </svg> to add the text before");
  std::ostringstream out;
  out.precision(6);
  for (const SvgText& t : texts) {
    out << "<text x=\"" << t.x << "\" y=\"" << t.y << "\" font-family=\"DejaVu Sans\" font-size=\"" << t.size
        << "\" fill=\"rgb(" << std::lround(255 * t.r) << "," << std::lround(255 * t.g) << "," << std::lround(255 * t.b)
        << ")\"";
    if (t.a < 1) out << " fill-opacity=\"" << t.a << "\"";
    if (t.bold) out << " font-weight=\"bold\"";
    if (t.halo > 0)
      out << " stroke=\"rgb(" << std::lround(255 * t.hr) << "," << std::lround(255 * t.hg) << ","
          << std::lround(255 * t.hb) << ")\" stroke-width=\"" << t.halo
          << "\" stroke-linejoin=\"round\" paint-order=\"stroke\"";
    if (std::abs(t.angle) > 1e-9) out << " transform=\"rotate(" << t.angle << " " << t.x << " " << t.y << ")\"";
    out << " xml:space=\"preserve\">" << escaped(t.text) << "</text>\n";
  }
  svg.insert(end, out.str());
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << svg;
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace softdrop::detail
