#version 450 core
// the plate, w = 0 in plate coordinates [mm]
layout(location = 0) in vec2 aPlate;

uniform mat4 uView;
uniform mat4 uProj;

out vec2 vPlate;

void main() {
  vPlate = aPlate;
  gl_Position = uProj * uView * vec4(aPlate, 0.0, 1.0);
}
