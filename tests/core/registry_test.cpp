#include "ferret/core/registry.hpp"

#include <gtest/gtest.h>

#include <string>

namespace ferret {
namespace {

struct Shape {
  virtual ~Shape() = default;
  [[nodiscard]] virtual double area() const = 0;
};

struct ShapeOptions {
  double size = 1.0;
};

struct Square final : Shape {
  explicit Square(const ShapeOptions& o) : side(o.size) {}
  [[nodiscard]] double area() const override { return side * side; }
  double side;
};

struct Disc final : Shape {
  explicit Disc(const ShapeOptions& o) : radius(o.size) {}
  [[nodiscard]] double area() const override { return 3.0 * radius * radius; }
  double radius;
};

using Shapes = Registry<Shape, ShapeOptions>;

Shapes shapes() {
  Shapes r;
  r.add("square", "four equal sides",
        [](const ShapeOptions& o) { return std::make_unique<Square>(o); });
  r.add("disc", "round", [](const ShapeOptions& o) { return std::make_unique<Disc>(o); });
  return r;
}

TEST(Registry, ADuplicateNameIsRefused) {
  Shapes r = shapes();
  EXPECT_THROW(
      r.add("disc", "again", [](const ShapeOptions& o) { return std::make_unique<Disc>(o); }),
      std::logic_error);
  EXPECT_EQ(r.names().size(), 2u);
}

TEST(Registry, AnEmptyFactoryIsRefused) {
  Shapes r;
  EXPECT_THROW(r.add("none", "", {}), std::logic_error);
  EXPECT_FALSE(r.contains("none"));
}

TEST(Registry, NamesKeepTheOrderOfRegistration) {
  Shapes r = shapes();
  r.add("a-last", "added last", [](const ShapeOptions& o) { return std::make_unique<Square>(o); });
  EXPECT_EQ(r.names(), (std::vector<std::string>{"square", "disc", "a-last"}));
  EXPECT_EQ(r.find("disc")->description, "round");
  EXPECT_EQ(r.find("circle"), nullptr);
}

TEST(Registry, ALabelDefaultsToTheName) {
  Shapes r = shapes();
  r.add(
      "box", "a square by another name",
      [](const ShapeOptions& o) { return std::make_unique<Square>(o); }, "Box");
  EXPECT_EQ(r.label("box"), "Box");
  EXPECT_EQ(r.label("disc"), "disc");
  EXPECT_EQ(r.label("cone"), "cone");
}

TEST(Registry, OptionsReachTheFactory) {
  const Shapes r = shapes();
  EXPECT_DOUBLE_EQ(r.make("square", ShapeOptions{3.0}, "--shape")->area(), 9.0);
  EXPECT_DOUBLE_EQ(r.make("disc", ShapeOptions{2.0}, "--shape")->area(), 12.0);
}

TEST(Registry, AnUnknownNameIsAnInputErrorNamingTheFieldAndTheChoices) {
  const Shapes r = shapes();
  EXPECT_TRUE(r.contains("disc"));
  EXPECT_FALSE(r.contains("triangle"));
  try {
    (void)r.make("triangle", ShapeOptions{}, "mission.yaml", "shapes.kind");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "mission.yaml");
    EXPECT_EQ(e.field(), "shapes.kind");
    EXPECT_EQ(e.expected(), "one of square, disc");
    EXPECT_STREQ(e.what(),
                 "mission.yaml: shapes.kind: expected one of square, disc (got triangle)");
  }
  EXPECT_THROW(r.check("triangle", "--shape"), InputError);
  EXPECT_NO_THROW(r.check("square", "--shape"));
}

int fills = 0;
void fill_shapes(Shapes& r) {
  ++fills;
  r.add("square", "four equal sides",
        [](const ShapeOptions& o) { return std::make_unique<Square>(o); });
}

TEST(Registry, AFilledRegistryIsFilledOnceWhenFirstAskedFor) {
  EXPECT_EQ(fills, 0);
  const Shapes& first = filled_registry<Shapes, fill_shapes>();
  const Shapes& again = filled_registry<Shapes, fill_shapes>();
  EXPECT_EQ(fills, 1);
  EXPECT_EQ(&first, &again);
  EXPECT_EQ(first.names(), (std::vector<std::string>{"square"}));
}

struct Kind {
  bool simulated = false;
};

TEST(Registry, EachEntryKeepsItsTraits) {
  Registry<Shape, ShapeOptions, Kind> r;
  r.add("square", "", [](const ShapeOptions& o) { return std::make_unique<Square>(o); });
  r.add(
      "disc", "", [](const ShapeOptions& o) { return std::make_unique<Disc>(o); }, "Disc",
      Kind{true});
  EXPECT_FALSE(r.traits("square").simulated);
  EXPECT_TRUE(r.traits("disc").simulated);
  EXPECT_EQ(r.label("disc"), "Disc");
  EXPECT_THROW((void)r.traits("triangle"), std::logic_error);
}

}  // namespace
}  // namespace ferret
