#version 100
#extension GL_OES_standard_derivatives : enable
#ifdef GL_ES
precision highp float;
#endif
precision mediump int;

uniform sampler2D uSampler;
uniform vec3 uKs;
uniform vec3 uLightPos;
uniform vec3 uCameraPos;
uniform vec3 uLightIntensity;
uniform sampler2D uShadowMap;

varying highp vec2 vTextureCoord;
varying highp vec3 vFragPos;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight;

#define NUM_SAMPLES 16
#define LIGHT_WIDTH_UV 0.03
#define NEAR_PLANE 0.01

vec2 poissonDisk[NUM_SAMPLES];

void spiralSamples(const in vec2 seed, const in float turns) {
  highp float angle = fract(sin(dot(seed, vec2(12.9898, 78.233))) * 43758.5453) * 6.2831853;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    highp float radius = pow((float(i) + 0.5) / float(NUM_SAMPLES), 0.75);
    poissonDisk[i] = radius * vec2(cos(angle), sin(angle));
    angle += 6.2831853 * turns / float(NUM_SAMPLES);
  }
}

float unpack(vec4 rgba) {
  return dot(rgba, vec4(1.0, 1.0 / 256.0, 1.0 / (256.0 * 256.0), 1.0 / (256.0 * 256.0 * 256.0)));
}

// Coordinates in NDC ([-1, 1]), mapped to uv here; the bias is in NDC too.
float findBlocker(sampler2D shadowMap, vec2 uvNdc, float zReceiverNdc, float searchRadiusUV, float biasNdc) {
  vec2 uv = uvNdc * 0.5 + 0.5;
  float sum = 0.0;
  float count = 0.0;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float zNdc = unpack(texture2D(shadowMap, uv + poissonDisk[i] * searchRadiusUV)) * 2.0 - 1.0;
    if (zNdc < zReceiverNdc - biasNdc) {
      sum += zNdc;
      count += 1.0;
    }
  }
  return count > 0.0 ? sum / count : -2.0;
}

float PCF(sampler2D shadowMap, vec4 coordsNdc, float filterRadiusUV, float biasNdc) {
  vec2 uv = coordsNdc.xy * 0.5 + 0.5;
  float lit = 0.0;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float zNdc = unpack(texture2D(shadowMap, uv + poissonDisk[i] * filterRadiusUV)) * 2.0 - 1.0;
    lit += step(coordsNdc.z - biasNdc, zNdc);
  }
  return lit / float(NUM_SAMPLES);
}

float PCSS(sampler2D shadowMap, vec4 coordsNdc, float biasNdc) {
  spiralSamples(coordsNdc.xy, 7.0);
  float zBlocker = findBlocker(shadowMap, coordsNdc.xy, coordsNdc.z, LIGHT_WIDTH_UV, biasNdc);
  if (zBlocker < -1.5) {
    return 1.0;
  }
  float penumbraUV = max((coordsNdc.z - zBlocker) / (zBlocker + 1.0 + NEAR_PLANE), 0.0) * LIGHT_WIDTH_UV;
  return PCF(shadowMap, coordsNdc, penumbraUV, biasNdc);
}

float useShadowMap(sampler2D shadowMap, vec4 shadowCoordNdc, float biasNdc) {
  float zNdc = unpack(texture2D(shadowMap, shadowCoordNdc.xy * 0.5 + 0.5)) * 2.0 - 1.0;
  return shadowCoordNdc.z - biasNdc > zNdc ? 0.0 : 1.0;
}

void main(void) {
  highp vec4 ndc = vec4(vPositionFromLight.xyz / vPositionFromLight.w, 1.0);
  float bias = max(0.005 * (1.0 - dot(normalize(vNormal), normalize(uLightPos))), 0.001);
  float visibility = PCSS(uShadowMap, ndc, bias) * 0.5 + useShadowMap(uShadowMap, ndc, bias) * 0.5;
  vec3 color = texture2D(uSampler, vTextureCoord).rgb;
  gl_FragColor = vec4(color * visibility, 1.0);
}
