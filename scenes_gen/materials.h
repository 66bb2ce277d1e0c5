#pragma once
// Small constructors for the materials the generators use.

#include "tracer/scene.h"

#include <string>

namespace scenes_gen {

inline tracer::Material diffuse(std::string name, tracer::Color albedo, float specular = 0.0f,
                                float shininess = 32.0f) {
  tracer::Material m;
  m.name = std::move(name);
  m.type = tracer::MaterialType::Diffuse;
  m.albedo = albedo;
  m.specular = specular;
  m.shininess = shininess;
  return m;
}

inline tracer::Material mirror(std::string name, tracer::Color reflectance) {
  tracer::Material m;
  m.name = std::move(name);
  m.type = tracer::MaterialType::Mirror;
  m.reflectance = reflectance;
  return m;
}

inline tracer::Material glass(std::string name, float ior,
                              tracer::Color absorption = tracer::Color(0.0f)) {
  tracer::Material m;
  m.name = std::move(name);
  m.type = tracer::MaterialType::Dielectric;
  m.ior = ior;
  m.absorption = absorption;
  return m;
}

inline tracer::PointLight point_light(tracer::Vec3 position, float power_w,
                                      tracer::Color color = tracer::Color(1.0f)) {
  tracer::PointLight l;
  l.position = position;
  l.power_w = power_w;
  l.color = color;
  return l;
}

}  // namespace scenes_gen
