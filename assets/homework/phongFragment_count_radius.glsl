#ifdef GL_ES
precision mediump float;
#endif

// Mistake: findBlocker sizes its disk with the sample count (64) as a radius in texels, far wider
// than the light; over that disk the floor, sloped to the light, rises in front of the receiver by
// more than the bias, so the receiver counts as its own blocker. Expected finding:
// receiver_counts_as_blocker (naming the bias's line 32 and the radius's line 71).
uniform sampler2D uSampler;
uniform vec3 uKd;
uniform vec3 uKs;
uniform vec3 uLightPos;
uniform vec3 uCameraPos;
uniform vec3 uLightIntensity;

varying highp vec2 vTextureCoord;
varying highp vec3 vFragPos;
varying highp vec3 vNormal;

#define NUM_SAMPLES 64
#define BLOCKER_SEARCH_NUM_SAMPLES NUM_SAMPLES
#define PCF_NUM_SAMPLES NUM_SAMPLES
#define NUM_RINGS 10

#define EPS 1e-3
#define PI 3.141592653589793
#define PI2 6.283185307179586

// The light is 5 world units wide; the light's frustum (DirectionalLight.js) is 200 wide.
#define LIGHT_WIDTH_UV (5.0 / 200.0)
// A constant bias in the map's depth units ([0, 1] over near..far).
#define BIAS 0.003

uniform sampler2D uShadowMap;

varying vec4 vPositionFromLight;

highp float rand_1to1(highp float x) {
  return fract(sin(x) * 10000.0);
}

highp float rand_2to1(vec2 uv) {
  highp float along = dot(uv.xy, vec2(12.9898, 78.233));
  highp float wrapped = mod(along, PI);
  return fract(sin(wrapped) * 43758.5453);
}

float unpack(vec4 rgbaDepth) {
  const vec4 weights = vec4(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0);
  return dot(rgbaDepth, weights);
}

vec2 poissonDisk[NUM_SAMPLES];

void poissonDiskSamples(const in vec2 randomSeed) {
  float turn = PI2 * float(NUM_RINGS) / float(NUM_SAMPLES);
  float angle = rand_2to1(randomSeed) * PI2;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float radius = pow(float(i + 1) / float(NUM_SAMPLES), 0.75);
    poissonDisk[i] = radius * vec2(cos(angle), sin(angle));
    angle += turn;
  }
}

// The blockers' average depth within the light's half width; -1 where there is none.
float findBlocker(sampler2D shadowMap, vec2 uv, float zReceiver) {
  poissonDiskSamples(uv);
  float depthSum = 0.0;
  int blockers = 0;
  for (int i = 0; i < BLOCKER_SEARCH_NUM_SAMPLES; i++) {
    float depth = unpack(texture2D(shadowMap, uv + poissonDisk[i] * float(BLOCKER_SEARCH_NUM_SAMPLES) / 2048.0));
    if (depth + BIAS < zReceiver) {
      depthSum += depth;
      blockers++;
    }
  }
  if (blockers == 0) {
    return -1.0;
  }
  return depthSum / float(blockers);
}

// The share of the filter's taps that see the light.
float PCF(sampler2D shadowMap, vec4 coords, float radiusUV) {
  poissonDiskSamples(coords.xy);
  float lit = 0.0;
  for (int i = 0; i < PCF_NUM_SAMPLES; i++) {
    float depth = unpack(texture2D(shadowMap, coords.xy + poissonDisk[i] * radiusUV));
    lit += coords.z <= depth + BIAS ? 1.0 : 0.0;
  }
  return lit / float(PCF_NUM_SAMPLES);
}

float PCSS(sampler2D shadowMap, vec4 coords) {
  // STEP 1: the blockers' average depth
  float zBlocker = findBlocker(shadowMap, coords.xy, coords.z);
  if (zBlocker < 0.0) return 1.0;
  // STEP 2: the penumbra's width by similar triangles (a width: the filter's radius is half)
  float penumbraUV = (coords.z - zBlocker) / zBlocker * LIGHT_WIDTH_UV;
  // STEP 3: filter over it
  return PCF(shadowMap, coords, 0.5 * penumbraUV);
}

float useShadowMap(sampler2D shadowMap, vec4 shadowCoord) {
  float depth = unpack(texture2D(shadowMap, shadowCoord.xy));
  return step(shadowCoord.z, depth + BIAS);
}

vec3 blinnPhong() {
  vec3 albedo = pow(texture2D(uSampler, vTextureCoord).rgb, vec3(2.2));
  vec3 toLight = normalize(uLightPos);
  vec3 normal = normalize(vNormal);
  float distance2 = dot(uLightPos - vFragPos, uLightPos - vFragPos);
  vec3 irradiance = uLightIntensity / distance2;
  vec3 diffuse = max(dot(toLight, normal), 0.0) * irradiance * albedo;
  vec3 toCamera = normalize(uCameraPos - vFragPos);
  vec3 halfway = normalize(toLight + toCamera);
  vec3 specular = uKs * irradiance * pow(max(dot(halfway, normal), 0.0), 32.0);
  vec3 radiance = 0.05 * albedo + diffuse + specular;
  return pow(radiance, vec3(1.0 / 2.2));
}

void main(void) {
  vec3 shadowCoord = vPositionFromLight.xyz / vPositionFromLight.w * 0.5 + 0.5;
  float visibility;
  //visibility = useShadowMap(uShadowMap, vec4(shadowCoord, 1.0));
  //visibility = PCF(uShadowMap, vec4(shadowCoord, 1.0), 0.002);
  visibility = PCSS(uShadowMap, vec4(shadowCoord, 1.0));
  vec3 phongColor = blinnPhong();
  gl_FragColor = vec4(phongColor * visibility, 1.0);
}
