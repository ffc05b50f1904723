#version 450 core
// the root's shadow on the plate: drawn over the already drawn plate as a multiplier (blending
// dst * src), only over the plate region the shadow map covers
in vec2 vPlate;

uniform mat4 uLightViewProj;            // plate [mm] -> light clip space
uniform sampler2DShadow uShadowMap;     // root depth from the light (compare mode)

out vec4 fragColour;

void main() {
  // one depth-compare tap, bilinear in hardware (2 x 2 percentage-closer filtering)
  vec4 lc = uLightViewProj * vec4(vPlate, 0.0, 1.0);
  vec3 q = lc.xyz / lc.w * 0.5 + 0.5;
  float lit = texture(uShadowMap, vec3(q.xy, min(q.z, 1.0) - 2e-4));
  fragColour = vec4(vec3(mix(0.58, 1.0, lit)), 1.0);
}
