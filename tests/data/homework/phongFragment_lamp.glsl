#ifdef GL_ES
precision mediump float;
#endif

// Hard shadows from a lamp whose map holds distances to it over the far plane; what lies outside
// the lamp's frustum is taken as lit.
#define BIAS 0.005

uniform sampler2D uSampler;
uniform vec3 uKs;
uniform vec3 uLightPos;
uniform vec3 uCameraPos;
uniform vec3 uLightIntensity;
uniform float uLightFarPlane;
uniform sampler2D uShadowMap;

varying highp vec2 vTextureCoord;
varying highp vec3 vFragPos;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight;

float unpack(vec4 rgbaDepth) {
  const vec4 bitShift = vec4(1.0, 1.0 / 256.0, 1.0 / (256.0 * 256.0), 1.0 / (256.0 * 256.0 * 256.0));
  return dot(rgbaDepth, bitShift);
}

float useShadowMap(sampler2D shadowMap, vec4 shadowCoord) {
  float stored = unpack(texture2D(shadowMap, shadowCoord.xy));
  return shadowCoord.z - BIAS > stored ? 0.0 : 1.0;
}

void main(void) {
  vec3 coord = vPositionFromLight.xyz / vPositionFromLight.w * 0.5 + 0.5;
  float distanceToLight = length(vFragPos - uLightPos) / uLightFarPlane;
  float visibility;
  if (coord.x < 0.0 || coord.x > 1.0 || coord.y < 0.0 || coord.y > 1.0) {
    visibility = 1.0;
  } else {
    visibility = useShadowMap(uShadowMap, vec4(coord.xy, distanceToLight, 1.0));
  }
  vec3 albedo = pow(texture2D(uSampler, vTextureCoord).rgb, vec3(2.2));
  vec3 toLight = normalize(uLightPos - vFragPos);
  float distance2 = dot(uLightPos - vFragPos, uLightPos - vFragPos);
  vec3 diffuse = max(dot(toLight, normalize(vNormal)), 0.0) * uLightIntensity / distance2 * albedo;
  gl_FragColor = vec4(pow(0.05 * albedo + diffuse * visibility, vec3(1.0 / 2.2)), 1.0);
}
