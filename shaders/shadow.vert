#version 450 core
// depth of the root seen from the key light (shadow map pass); positions in plate coordinates [mm]
layout(location = 0) in vec3 aPos;

uniform mat4 uLightViewProj;

void main() {
  gl_Position = uLightViewProj * vec4(aPos, 1.0);
}
