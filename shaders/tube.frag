#version 450 core
// Phong-style shading; stripes chosen per pixel from the interpolated (d1, d2) direction so their
// edges stay sharp and straight at any tube resolution
in vec3 vPlate;
in vec3 vNormalPlate;
in vec3 vPosEye;
in vec3 vNormalEye;
in vec2 vSide;
in vec3 vColour;
in float vStriped;

uniform vec3 uLight;        // towards the key light, eye space, unit
uniform bool uOrtho;
uniform vec3 uBody;
uniform vec3 uPlus;         // +d1 stripe
uniform vec3 uMinus;        // -d1 stripe
uniform float uStripeCos;   // cos of the stripe half width
uniform vec4 uLighting;     // ambient, diffuse, specular, shininess
uniform bool uShadows;                // a strand of the root that hides the key light from another
uniform mat4 uLightViewProj;          // plate [mm] -> light clip space
uniform sampler2DShadow uShadowMap;   // root depth from the light (compare mode)
uniform vec3 uLightPlate;             // towards the key light, plate axes
uniform float uShadowTexel;           // one map texel [mm]

out vec4 fragColour;

void main() {
  vec3 base = vColour;
  if (vStriped > 0.5) {
    // striped 1: ivory body; striped 2: the vertex colour (--color-by) as the body
    vec3 body = vStriped > 1.5 ? vColour : uBody;
    float c = vSide.x / max(length(vSide), 1e-6);
    float aa = max(fwidth(c), 1e-4);
    float plus = smoothstep(uStripeCos - aa, uStripeCos + aa, c);
    float minus = smoothstep(uStripeCos - aa, uStripeCos + aa, -c);
    base = mix(mix(body, uPlus, plus), uMinus, minus);
    if (vStriped > 1.5) {
      // a dark outline on each stripe edge, so pink and orange read on every colour of the map
      float w = 0.05 + 1.5 * aa;
      float edge = max(1.0 - smoothstep(0.0, w, abs(c - uStripeCos)), 1.0 - smoothstep(0.0, w, abs(-c - uStripeCos)));
      base = mix(base, vec3(0.08), 0.85 * edge);
    }
  }
  vec3 N = normalize(vNormalEye);
  if (!gl_FrontFacing) N = -N;
  vec3 V = uOrtho ? vec3(0.0, 0.0, 1.0) : normalize(-vPosEye);
  vec3 L = normalize(uLight);
  vec3 H = normalize(L + V);
  float diff = max(dot(N, L), 0.0);
  if (uShadows) {
    // only surfaces facing the light can be shadowed by another strand (the rest is unlit anyway);
    // looked up 2.5 texels out along the normal, so a surface does not shadow itself (acne)
    vec3 Np = normalize(vNormalPlate);
    if (!gl_FrontFacing) Np = -Np;
    if (dot(Np, uLightPlate) > 0.0) {
      vec4 lc = uLightViewProj * vec4(vPlate + 2.5 * uShadowTexel * Np, 1.0);
      vec3 q = lc.xyz / lc.w * 0.5 + 0.5;
      diff *= texture(uShadowMap, vec3(q.xy, min(q.z, 1.0) - 1e-4));
    }
  }
  float fill = 0.18 * max(dot(N, normalize(vec3(0.6, -0.3, 0.6))), 0.0);
  float spec = diff > 0.0 ? pow(max(dot(N, H), 0.0), uLighting.w) : 0.0;
  vec3 col = base * (uLighting.x + uLighting.y * diff + fill) + uLighting.z * spec;
  fragColour = vec4(min(col, vec3(1.0)), 1.0);
}
