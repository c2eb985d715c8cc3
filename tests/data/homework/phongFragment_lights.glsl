#ifdef GL_ES
precision mediump float;
#endif

// Two lights in arrays indexed by light: a map, a matrix, a position and an intensity each,
// hard shadows, the lights' radiance summed before the gamma.
#define NUM_LIGHTS 2
#define BIAS 0.003

uniform sampler2D uSampler;
uniform vec3 uKd;
uniform vec3 uKs;
uniform vec3 uCameraPos;
uniform vec3 uLightPos[NUM_LIGHTS];
uniform vec3 uLightIntensity[NUM_LIGHTS];
uniform sampler2D uShadowMap[NUM_LIGHTS];

varying highp vec2 vTextureCoord;
varying highp vec3 vFragPos;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight[NUM_LIGHTS];

float unpack(vec4 rgbaDepth) {
  const vec4 bitShift = vec4(1.0, 1.0 / 256.0, 1.0 / (256.0 * 256.0), 1.0 / (256.0 * 256.0 * 256.0));
  return dot(rgbaDepth, bitShift);
}

float useShadowMap(sampler2D shadowMap, vec4 shadowCoord) {
  float depth = unpack(texture2D(shadowMap, shadowCoord.xy));
  return step(shadowCoord.z, depth + BIAS);
}

vec3 radiance(vec3 albedo, vec3 lightPos, vec3 lightIntensity) {
  vec3 toLight = normalize(lightPos);
  vec3 normal = normalize(vNormal);
  float distance2 = dot(lightPos - vFragPos, lightPos - vFragPos);
  vec3 irradiance = lightIntensity / distance2;
  vec3 diffuse = max(dot(toLight, normal), 0.0) * irradiance * albedo;
  vec3 halfway = normalize(toLight + normalize(uCameraPos - vFragPos));
  vec3 specular = uKs * irradiance * pow(max(dot(halfway, normal), 0.0), 32.0);
  return diffuse + specular;
}

void main(void) {
  vec3 albedo = pow(texture2D(uSampler, vTextureCoord).rgb, vec3(2.2));
  vec3 sum = 0.05 * albedo;
  for (int l = 0; l < NUM_LIGHTS; l++) {
    vec3 shadowCoord = vPositionFromLight[l].xyz / vPositionFromLight[l].w * 0.5 + 0.5;
    float visibility = useShadowMap(uShadowMap[l], vec4(shadowCoord, 1.0));
    sum += visibility * radiance(albedo, uLightPos[l], uLightIntensity[l]);
  }
  gl_FragColor = vec4(pow(sum, vec3(1.0 / 2.2)), 1.0);
}
