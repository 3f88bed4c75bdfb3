// Pictures drawn through the library (render_scene): every format at the asked size and not blank;
// the SVG parses, keeps its text as text and holds one circle per grain (plus periodic copies); a
// caption fits; the legend avoids the data; bad inputs leave no file.
#include "softdrop/render.hpp"

#include <cairo.h>
#include <gif_lib.h>
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "cli_run.hpp"
#include "picture_files.hpp"

namespace softdrop {
namespace {

using test::count_styled;
using test::fresh;
using test::Png;
using test::png_pixels;
using test::read_png;

Scene small_scene() {
  Scene s;
  s.medium = Medium{100, 80, true, {{50, 40, 10}, {20, 20, 8}, {97, 60, 9}}, nullptr};  // the last crosses x = W
  s.caption = "three grains";
  Polyline p;
  p.x = {50, 60, 110, 120};  // unwrapped: leaves through x = W and comes back at x = 0
  p.y = {90, 60, 30, -2};
  s.lines.push_back(p);
  return s;
}

TEST(Render, PngHasTheAskedWidthAndIsNotBlank) {
  const std::string out = fresh("scene.png");
  RenderStyle style;
  style.width = 320;
  render_scene(small_scene(), style, out);
  const Png png = read_png(out);
  EXPECT_EQ(png.width, 320);
  EXPECT_GT(png.height, 320 * 80 / 100);  // the box's aspect ratio plus the caption
  EXPECT_GT(png.non_background, 2000);
}

// A grain's fill darkens with its share (of the droplets that touched it): more ink for more share,
// and even the share of one droplet in fifty is seen against an unfilled grain.
TEST(Render, AGrainsFillDarkensWithItsShare) {
  const auto ink = [](double share) {
    Scene s;
    s.medium = Medium{100, 80, false, {{50, 40, 20}}, nullptr};
    s.filled = {share};
    s.caption = "";
    const std::string out = fresh("share.png");
    RenderStyle style;
    style.width = 200;
    render_scene(s, style, out);
    double sum = 0;
    for (const std::uint32_t p : png_pixels(out)) sum += 3 * 255 - ((p >> 16) & 0xff) - ((p >> 8) & 0xff) - (p & 0xff);
    return sum;
  };
  const double none = ink(0), least = ink(1.0 / 50), half = ink(0.5), whole = ink(1), beyond = ink(7);
  EXPECT_GT(least, 1.2 * none);
  EXPECT_GT(half, 1.5 * least);
  EXPECT_GT(whole, 1.2 * half);
  EXPECT_EQ(beyond, whole);  // a share is at most 1
}

// A caption longer than the picture is shrunk until the whole of it fits inside the margins: no
// pixel of it in the right margin, at any of these widths.
TEST(Render, ALongCaptionStaysInsideTheRightMargin) {
  Scene scene = small_scene();
  scene.caption =
      "run 1, generation 3: T = 1.4711, 19 grains touched (filled); 20 grains, porosity 0.7611, "
      "500 x 500, periodic in x";
  for (const int width : {200, 400, 800}) {
    SCOPED_TRACE(width);
    const std::string out = fresh("long_caption.png");
    RenderStyle style;
    style.width = width;
    render_scene(scene, style, out);
    cairo_surface_t* png = cairo_image_surface_create_from_png(out.c_str());
    ASSERT_EQ(cairo_surface_status(png), CAIRO_STATUS_SUCCESS);
    const int h = cairo_image_surface_get_height(png), stride = cairo_image_surface_get_stride(png);
    const unsigned char* data = cairo_image_surface_get_data(png);
    const auto background = *reinterpret_cast<const std::uint32_t*>(data);
    long in_margin = 0, caption = 0;
    const int band = static_cast<int>(std::max(11.0, 0.02 * width) * 1.6);  // the caption's rows
    for (int y = h - static_cast<int>(style.margin) - band; y < h; ++y)
      for (int x = 0; x < width; ++x) {
        const bool ink = reinterpret_cast<const std::uint32_t*>(data + y * stride)[x] != background;
        caption += ink;
        in_margin += ink && x >= width - static_cast<int>(style.margin);
      }
    cairo_surface_destroy(png);
    EXPECT_GT(caption, 100);  // the caption is drawn
    EXPECT_EQ(in_margin, 0);
  }
}

TEST(Render, SvgParsesAndHasOneCirclePerGrainPlusPeriodicCopies) {
  const std::string out = fresh("scene.svg");
  RenderStyle style;
  style.grain = parse_colour("#ff0000");
  render_scene(small_scene(), style, out);
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile(out.c_str()), tinyxml2::XML_SUCCESS);
  ASSERT_STREQ(doc.RootElement()->Name(), "svg");
  EXPECT_EQ(count_styled(doc.RootElement(), "stroke:rgb(100%,0%,0%)"), 3 + 1);
  Scene walls = small_scene();
  walls.medium.periodic = false;
  walls.medium.grains[2].x = 80;
  render_scene(walls, style, out);
  ASSERT_EQ(doc.LoadFile(out.c_str()), tinyxml2::XML_SUCCESS);
  EXPECT_EQ(count_styled(doc.RootElement(), "stroke:rgb(100%,0%,0%)"), 3);
}

// Words stay words in SVG: the caption, a chart's labels and ticks are <text> elements (the y
// label turned by -90 degrees), with the characters escaped, and no glyph outlines.
TEST(Render, SvgKeepsItsTextAsText) {
  const std::string scene = fresh("text_scene.svg"), chart = fresh("text_chart.svg");
  Scene s = small_scene();
  s.caption = "3 grains & a <caption>";
  render_scene(s, RenderStyle{}, scene);
  Chart c;
  Series line;
  line.x = {0.6, 0.8, 1.0};
  line.y = {1.5, 1.3, 1.0};
  line.label = "a − c φᵇ";
  c.series = {line};
  c.x_label = "porosity φ";
  c.y_label = "tortuosity ⟨T⟩";
  render_chart(c, RenderStyle{}, chart);
  auto texts = [](const std::string& path) {
    tinyxml2::XMLDocument doc;
    EXPECT_EQ(doc.LoadFile(path.c_str()), tinyxml2::XML_SUCCESS);
    std::vector<std::pair<std::string, std::string>> out;  // text, transform
    for (const tinyxml2::XMLElement* e = doc.RootElement()->FirstChildElement("text"); e;
         e = e->NextSiblingElement("text"))
      out.emplace_back(e->GetText() ? e->GetText() : "", e->Attribute("transform") ? e->Attribute("transform") : "");
    return out;
  };
  const auto in_scene = texts(scene);
  ASSERT_EQ(in_scene.size(), 1u);
  EXPECT_EQ(in_scene[0].first, "3 grains & a <caption>");
  const auto in_chart = texts(chart);
  bool x_label = false, y_label = false, legend = false;
  for (const auto& [text, transform] : in_chart) {
    x_label |= text == "porosity φ" && transform.empty();
    y_label |= text == "tortuosity ⟨T⟩" && transform.rfind("rotate(-90 ", 0) == 0;
    legend |= text == "a − c φᵇ";
  }
  EXPECT_TRUE(x_label && y_label && legend);
  EXPECT_GE(in_chart.size(), 3u + 4u);  // the labels, the legend and the ticks
  std::ifstream in(chart);
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(svg.find("glyph"), std::string::npos) << "no glyph outlines";
}

// The legend goes to the corner the data leave free: top left over a rising line, top right over a
// falling one, bottom right when the data fill the top.
TEST(Render, TheLegendSitsWhereTheDataAreNot) {
  struct Case {
    std::vector<double> y;
    bool legend_left, legend_top;
  };
  for (const Case& c :
       {Case{{1, 2, 3, 4, 5}, true, true}, Case{{5, 4, 3, 2, 1}, false, true}, Case{{5, 5, 1, 5, 5}, false, false}}) {
    const std::string svg = fresh("legend.svg");
    Chart chart;
    Series line;
    line.x = {0, 1, 2, 3, 4};
    line.y = c.y;
    line.label = "a legend entry";
    chart.series = {line};
    RenderStyle style;
    style.width = 400;
    render_chart(chart, style, svg);
    tinyxml2::XMLDocument doc;
    ASSERT_EQ(doc.LoadFile(svg.c_str()), tinyxml2::XML_SUCCESS);
    double x = -1, y = -1;
    for (const tinyxml2::XMLElement* e = doc.RootElement()->FirstChildElement("text"); e;
         e = e->NextSiblingElement("text"))
      if (e->GetText() && std::string(e->GetText()) == "a legend entry")
        x = e->DoubleAttribute("x"), y = e->DoubleAttribute("y");
    ASSERT_GE(x, 0) << "no legend";
    SCOPED_TRACE(c.y[0]);
    EXPECT_EQ(x < 200, c.legend_left) << x;
    EXPECT_EQ(y < 124, c.legend_top) << y;
  }
}

TEST(Render, PdfAndChartAreWritten) {
  const std::string pdf = fresh("scene.pdf");
  render_scene(small_scene(), RenderStyle{}, pdf);
  std::ifstream in(pdf, std::ios::binary);
  std::string head(5, '\0');
  in.read(head.data(), 5);
  EXPECT_EQ(head, "%PDF-");
  const std::string chart = fresh("chart.png");
  Chart c;
  Series steps;
  steps.x = {0, 3, 8, 20};
  steps.y = {1.1, 1.12, 1.15, 1.2};
  steps.style = Series::Style::steps;
  steps.label = "best";
  Series dots = steps;
  dots.style = Series::Style::points;
  dots.err = {0.01, 0.01, 0.02, 0.01};
  c.series = {steps, dots};
  c.markers = {5};
  c.marker_labels = {"enters"};
  c.x_label = "generation";
  c.y_label = "best T";
  RenderStyle style;
  style.width = 400;
  render_chart(c, style, chart);
  const Png png = read_png(chart);
  EXPECT_EQ(png.width, 400);
  EXPECT_EQ(png.height, 248);
  EXPECT_GT(png.non_background, 1500);
  Series bad = steps;
  bad.err = {1};
  c.series = {bad};
  EXPECT_THROW(render_chart(c, style, fresh("bad_chart.png")), std::invalid_argument);
  c.series.clear();
  c.markers.clear();
  EXPECT_THROW(render_chart(c, style, fresh("empty_chart.png")), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(fresh("bad_chart.png")));
}

TEST(Render, AnimationIsALoopingGifWithOneImagePerFrame) {
  const std::string out = fresh("anim.gif");
  RenderStyle style;
  style.width = 200;
  render_animation(
      7, 10,
      [](int f, Scene& s) {
        s = small_scene();
        s.top_room = 20;
        s.lines[0].x.resize(static_cast<std::size_t>(1 + f % 4));
      },
      style, out);
  int error = 0;
  GifFileType* gif = DGifOpenFileName(out.c_str(), &error);
  ASSERT_NE(gif, nullptr);
  ASSERT_EQ(DGifSlurp(gif), GIF_OK);
  EXPECT_EQ(gif->ImageCount, 7);
  EXPECT_EQ(gif->SWidth, 200);
  GraphicsControlBlock gcb;
  ASSERT_EQ(DGifSavedExtensionToGCB(gif, 1, &gcb), GIF_OK);
  EXPECT_EQ(gcb.DelayTime, 10);  // centiseconds at 10 fps
  bool loops = false;            // the NETSCAPE2.0 application extension, before the first frame
  for (int i = 0; i < gif->SavedImages[0].ExtensionBlockCount; ++i) {
    const ExtensionBlock& b = gif->SavedImages[0].ExtensionBlocks[i];
    loops |= b.Function == APPLICATION_EXT_FUNC_CODE && b.ByteCount == 11 &&
             std::string(reinterpret_cast<const char*>(b.Bytes), 11) == "NETSCAPE2.0";
  }
  EXPECT_TRUE(loops);
  long coloured = 0;
  const SavedImage& frame = gif->SavedImages[3];
  for (int i = 0; i < frame.ImageDesc.Width * frame.ImageDesc.Height; ++i)
    coloured += frame.RasterBits[i] != frame.RasterBits[0];
  EXPECT_GT(coloured, 500);
  DGifCloseFile(gif, &error);
}

TEST(Render, AShakenImageMediumIsDrawnWhereItHasMovedAndWrapsAround) {
  // A 100 x 100 periodic box whose left 40 % is solid.
  PoreImage im;
  im.nx = im.ny = 10;
  im.pixel = 10;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) im.pore.push_back(i < 4 ? 0 : 1);
  RenderStyle style;
  style.width = 240;
  const auto draw = [&](double sx, double sy, const std::string& name) {
    Scene s;
    s.medium = image_medium(im);
    s.image_shift_x = sx, s.image_shift_y = sy;
    const std::string out = fresh(name);
    render_scene(s, style, out);
    return out;
  };
  const auto still = png_pixels(draw(0, 0, "image_still.png"));
  const auto half = png_pixels(draw(50, 0, "image_half.png"));
  const auto whole = png_pixels(draw(100, 0, "image_whole.png"));
  ASSERT_FALSE(still.empty());
  EXPECT_EQ(whole, still) << "moved by the width, a periodic image is where it was";
  EXPECT_NE(half, still) << "moved by half the width, the solid is elsewhere";
  // The same solid area either way: what leaves at x = W comes back at x = 0.
  EXPECT_EQ(read_png(fresh("image_half.png")).non_background, read_png(fresh("image_still.png")).non_background);
  EXPECT_NE(png_pixels(draw(0, 5, "image_down.png")), still) << "a shake along y moves it too";
}

TEST(Render, BadFormatAndColourAreRefusedWithoutAFile) {
  EXPECT_THROW(render_scene(small_scene(), RenderStyle{}, fresh("scene.bmp")), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(fresh("scene.bmp")));
  EXPECT_THROW(render_scene(small_scene(), RenderStyle{}, fresh("still.gif")), std::invalid_argument);
  EXPECT_THROW(parse_colour("red"), std::invalid_argument);
  EXPECT_THROW(parse_colour("#12345g"), std::invalid_argument);
  EXPECT_EQ(parse_colour("#ff000080"), (Rgba{1, 0, 0, 128 / 255.0}));
  EXPECT_EQ(parse_colour("00ff00"), (Rgba{0, 1, 0, 1}));
  EXPECT_THROW(parse_colour("#ff00"), std::invalid_argument);
  EXPECT_THROW(parse_colour(""), std::invalid_argument);
}

}  // namespace
}  // namespace softdrop
