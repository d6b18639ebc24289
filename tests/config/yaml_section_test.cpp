// The one config reader (drivers/strict_yaml YamlSection): each getter's value and each
// refusal's source, key path, value as written and expectation.
#include "wavebench/strict_yaml/yaml_section.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace wavebench::strict_yaml {
namespace {

// The section "brake.link" of a file "bench.yaml" holding `body` (a flow mapping).
YamlSection link(const std::string& body) {
  return YamlSection(YAML::Load(body), "brake.link", "bench.yaml");
}

RefusedConfig refusal(const std::string& body, const std::function<void(YamlSection&)>& read) {
  YamlSection s = link(body);
  try {
    read(s);
  } catch (const RefusedConfig& e) {
    EXPECT_EQ(e.source(), "bench.yaml") << e.what();
    const std::string what = e.what();
    EXPECT_EQ(what,
              "bench.yaml: " + e.key() + ": got '" + e.value() + "', expected " + e.expected());
    return e;
  }
  ADD_FAILURE() << "accepted: " << body;
  return RefusedConfig("", "", "");
}

bool says(const RefusedConfig& e, const std::string& part) {
  return e.expected().find(part) != std::string::npos;
}

TEST(YamlSection, QuantitiesAreSiWithUnitsOfTheirDimension) {
  YamlSection s = link("{timeout: 250 ms, speed: 3000 rpm, plain: 2.5}");
  EXPECT_DOUBLE_EQ(s.quantity("timeout", Dimension::kTime), 0.25);
  EXPECT_NEAR(*s.optional_quantity("speed", Dimension::kAngularSpeed), 314.159265, 1e-6);
  EXPECT_DOUBLE_EQ(s.quantity_or("plain", Dimension::kTime, 9), 2.5);
  EXPECT_DOUBLE_EQ(s.quantity_or("absent", Dimension::kTime, 9), 9);
  EXPECT_FALSE(s.optional_quantity("other", Dimension::kTime));
  EXPECT_NO_THROW(s.finish());
}

TEST(YamlSection, QuantityRefusalsNameKeyPathValueAndExpectation) {
  auto e =
      refusal("{timeout: 3 N*m}", [](YamlSection& s) { s.quantity("timeout", Dimension::kTime); });
  EXPECT_EQ(e.key(), "brake.link.timeout");
  EXPECT_EQ(e.value(), "3 N*m");
  EXPECT_TRUE(says(e, "a time")) << e.what();
  EXPECT_TRUE(says(e, "is a torque")) << e.what();

  e = refusal("{}", [](YamlSection& s) { s.quantity("timeout", Dimension::kTime); });
  EXPECT_EQ(e.key(), "brake.link.timeout");
  EXPECT_TRUE(says(e, "required")) << e.what();

  e = refusal("{timeout: .inf}", [](YamlSection& s) { s.quantity("timeout", Dimension::kTime); });
  EXPECT_EQ(e.value(), ".inf");
  EXPECT_TRUE(says(e, "finite")) << e.what();

  e = refusal("{timeout: -1 s}",
              [](YamlSection& s) { s.positive_quantity("timeout", Dimension::kTime); });
  EXPECT_EQ(e.value(), "-1 s");
  EXPECT_TRUE(says(e, "> 0")) << e.what();

  e = refusal("{timeout: 2 min}", [](YamlSection& s) {
    s.optional_quantity_in("timeout", Dimension::kTime, 0, 60, "a time in [0, 60 s]");
  });
  EXPECT_EQ(e.value(), "2 min");
  EXPECT_EQ(e.expected(), "a time in [0, 60 s]");

  e = refusal("{steps: [1 s, 2 Hz]}",
              [](YamlSection& s) { s.quantity_list("steps", Dimension::kTime); });
  EXPECT_EQ(e.key(), "brake.link.steps[1]");
  EXPECT_EQ(e.value(), "2 Hz");
}

TEST(YamlSection, AKeyWithoutAValueIsRefusedNotDefaulted) {
  auto e = refusal("{limit: }",
                   [](YamlSection& s) { s.optional_quantity("limit", Dimension::kTorque); });
  EXPECT_EQ(e.key(), "brake.link.limit");
  EXPECT_EQ(e.value(), "");
  EXPECT_TRUE(says(e, "leave the key out")) << e.what();
  e = refusal("{port: ~}", [](YamlSection& s) { s.integer_or("port", 0, 65535, 502); });
  EXPECT_TRUE(says(e, "leave the key out")) << e.what();
  e = refusal("{map: null}", [](YamlSection& s) { s.optional_section("map"); });
  EXPECT_TRUE(says(e, "leave the key out")) << e.what();
}

TEST(YamlSection, NumbersAndIntegersWithinTheirRange) {
  YamlSection s = link("{scale: 1e-3, port: 502, id: 0x1A, fraction: [3, 4]}");
  EXPECT_DOUBLE_EQ(*s.optional_number("scale", -1, 1), 1e-3);
  EXPECT_EQ(s.integer("port", 0, 65535), 502);
  EXPECT_EQ(*s.optional_integer("id", 0, 255), 0x1A);
  EXPECT_EQ(*s.optional_integer_list("fraction", 0, 10), (std::vector<long long>{3, 4}));
  EXPECT_DOUBLE_EQ(s.number_or("absent", 0, 1, 0.5), 0.5);

  auto e = refusal("{scale: 2}", [](YamlSection& r) { r.optional_number("scale", -1, 1); });
  EXPECT_EQ(e.key(), "brake.link.scale");
  EXPECT_EQ(e.value(), "2");
  EXPECT_EQ(e.expected(), "a number in [-1, 1]");
  e = refusal("{scale: fast}", [](YamlSection& r) { r.number_or("scale", -1, 1, 0); });
  EXPECT_EQ(e.value(), "fast");
  e = refusal("{scale: 1 mm}", [](YamlSection& r) { r.number_or("scale", -1, 1, 0); });
  EXPECT_EQ(e.value(), "1 mm");  // a plain number takes no unit

  e = refusal("{port: 70000}", [](YamlSection& r) { r.integer("port", 0, 65535); });
  EXPECT_EQ(e.key(), "brake.link.port");
  EXPECT_EQ(e.value(), "70000");
  EXPECT_EQ(e.expected(), "an integer in [0, 65535]");
  e = refusal("{port: 1.5}", [](YamlSection& r) { r.optional_integer("port", 0, 65535); });
  EXPECT_EQ(e.value(), "1.5");
  e = refusal("{port: [1]}", [](YamlSection& r) { r.optional_integer("port", 0, 65535); });
  EXPECT_EQ(e.value(), "[1]");
  e = refusal("{}", [](YamlSection& r) { r.integer("port", 0, 65535); });
  EXPECT_TRUE(says(e, "required")) << e.what();
  e = refusal("{fraction: [3, -4]}",
              [](YamlSection& r) { r.optional_integer_list("fraction", 0, 10); });
  EXPECT_EQ(e.key(), "brake.link.fraction[1]");
  EXPECT_EQ(e.value(), "-4");
}

TEST(YamlSection, TextBooleanAndChoice) {
  YamlSection s = link("{host: bench-1, on: true, parity: E, names: [a, b]}");
  EXPECT_EQ(s.text("host"), "bench-1");
  EXPECT_TRUE(s.boolean_or("on", false));
  EXPECT_EQ(s.choice("parity", {"N", "E", "O"}), "E");
  EXPECT_EQ(*s.optional_text_list("names"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(s.choice_or("absent", {"x"}, "x"), "x");

  auto e = refusal("{host: {a: 1}}", [](YamlSection& r) { r.text("host"); });
  EXPECT_EQ(e.key(), "brake.link.host");
  EXPECT_EQ(e.value(), "{a: 1}");
  EXPECT_EQ(e.expected(), "a text value");
  e = refusal("{on: maybe}", [](YamlSection& r) { r.boolean_or("on", false); });
  EXPECT_EQ(e.value(), "maybe");
  EXPECT_EQ(e.expected(), "true or false");
  e = refusal("{parity: Q}", [](YamlSection& r) { r.optional_choice("parity", {"N", "E", "O"}); });
  EXPECT_EQ(e.key(), "brake.link.parity");
  EXPECT_EQ(e.value(), "Q");
  EXPECT_EQ(e.expected(), "one of N|E|O");
  e = refusal("{names: [a, [b]]}", [](YamlSection& r) { r.optional_text_list("names"); });
  EXPECT_EQ(e.key(), "brake.link.names[1]");
}

TEST(YamlSection, SubSectionsCarryTheirKeyPathAndSource) {
  YamlSection s = link("{tcp: {port: 1502}, items: [{a: 1}, {a: 2}]}");
  YamlSection tcp = s.section("tcp");
  EXPECT_EQ(tcp.path(), "brake.link.tcp");
  EXPECT_EQ(tcp.source(), "bench.yaml");
  EXPECT_EQ(tcp.integer("port", 0, 65535), 1502);
  const auto items = s.section_list("items");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[1].path(), "brake.link.items[1]");

  auto e = refusal("{tcp: {port: x}}",
                   [](YamlSection& r) { r.section("tcp").integer("port", 0, 65535); });
  EXPECT_EQ(e.key(), "brake.link.tcp.port");
  e = refusal("{tcp: 5}", [](YamlSection& r) { r.optional_section("tcp"); });
  EXPECT_EQ(e.key(), "brake.link.tcp");
  EXPECT_EQ(e.value(), "5");
  e = refusal("{items: [{a: 1}, 3]}", [](YamlSection& r) { r.section_list("items"); });
  EXPECT_EQ(e.key(), "brake.link.items[1]");
  EXPECT_EQ(e.value(), "3");
}

TEST(YamlSection, FinishRefusesUnreadKeysSuggestingTheNearOne) {
  auto e = refusal("{port: 1, prot: 2}", [](YamlSection& r) {
    r.integer_or("port", 0, 65535, 0);
    r.finish();
  });
  EXPECT_EQ(e.key(), "brake.link.prot");
  EXPECT_EQ(e.value(), "2");
  EXPECT_TRUE(says(e, "did you mean 'port'")) << e.what();

  e = refusal("{port: 1, colour: red}", [](YamlSection& r) {
    r.integer_or("port", 0, 65535, 0);
    r.text_or("host", "");
    r.finish();
  });
  EXPECT_EQ(e.key(), "brake.link.colour");
  EXPECT_TRUE(says(e, "this section knows: host, port")) << e.what();

  // A required key that is missing points at its look-alike.
  e = refusal("{hots: a}", [](YamlSection& r) { r.text("host"); });
  EXPECT_EQ(e.key(), "brake.link.host");
  EXPECT_TRUE(says(e, "'hots': a misspelling?")) << e.what();
}

TEST(YamlSection, DocumentSectionRefusesANonMapping) {
  try {
    (void)document_section(YAML::Load("[1, 2]"), "opts.yaml", "a mapping of options");
    ADD_FAILURE() << "accepted a list";
  } catch (const RefusedConfig& e) {
    EXPECT_EQ(std::string(e.what()),
              "opts.yaml: (document): got '[1, 2]', expected a mapping of options");
  }
}

}  // namespace
}  // namespace wavebench::strict_yaml
