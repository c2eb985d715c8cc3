#ifdef GL_ES
precision mediump float;
#endif

uniform sampler2D uSampler;
uniform sampler2D uShadowMap;
uniform vec3 uLightPos;

varying highp vec2 vTextureCoord;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight;

#define NUM_SAMPLES 8
#define SEARCH_UV 0.01

float unpack(vec4 rgba) {
  return dot(rgba, vec4(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0));
}

// A prototype, defined below.
float PCF(sampler2D shadowMap, vec4 coords);

// A helper that takes the map: the depth stored at one uv.
float depthAt(sampler2D map, vec2 uv) {
  return unpack(texture2D(map, uv));
}

float ring(sampler2D map, vec2 uv, float radius, float zReceiver) {
  float lit = 0.0;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float angle = 6.2831853 * float(i) / float(NUM_SAMPLES);
    lit += step(zReceiver, depthAt(map, uv + radius * vec2(cos(angle), sin(angle))) + 0.002);
  }
  return lit / float(NUM_SAMPLES);
}

// No final return: legal GLSL, what a driver returns when no blocker is found is undefined.
float findBlocker(sampler2D shadowMap, vec2 uv, float zReceiver) {
  float sum = 0.0;
  int blockers = 0;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float angle = 6.2831853 * float(i) / float(NUM_SAMPLES);
    float depth = depthAt(shadowMap, uv + SEARCH_UV * vec2(cos(angle), sin(angle)));
    if (depth < zReceiver - 0.002) {
      sum += depth;
      blockers += 1;
    }
  }
  if (blockers > 0) {
    return sum / float(blockers);
  }
}

vec2 noBlockerYet(float z) {
  if (z > 0.0) return vec2(z);
}

float PCF(sampler2D shadowMap, vec4 coords) {
  return ring(shadowMap, coords.xy, 0.002, coords.z) * 0.5 + ring(shadowMap, coords.xy, 0.004, coords.z) * 0.5;
}

void main() {
  vec3 coords = vPositionFromLight.xyz / vPositionFromLight.w * 0.5 + 0.5;
  float blocker = findBlocker(uShadowMap, coords.xy, coords.z);
  float hard = step(coords.z, unpack(texture2D(uShadowMap, coords.xy)) + 0.002);
  float visibility = blocker > 0.0 ? PCF(uShadowMap, vec4(coords, 1.0)) : hard + noBlockerYet(blocker).x * 0.0;
  float light = max(dot(normalize(vNormal), normalize(uLightPos)), 0.0);
  gl_FragColor = vec4(texture2D(uSampler, vTextureCoord).rgb * light * visibility, 1.0);
}
