// Mistake: the orthographic box is only 160 world units tall (bottom/top ±80). shadowlab's check
// scene fits inside it, but the framework's own floor reaches 100 world units up the map from the
// light's axis: its far band, z under about -115, wraps (REPEAT) to rows nothing was drawn in,
// reads depth 0 and is black in the student's page. Expected finding: light_frustum_clips (on
// the framework's floor).
class DirectionalLight {
  constructor(lightIntensity, lightColor, lightPos, focalPoint, lightUp, hasShadowMap, gl) {
    this.mesh = Mesh.cube(setTransform(0, 0, 0, 0.2, 0.2, 0.2, 0));
    this.mat = new EmissiveMaterial(lightIntensity, lightColor);
    this.lightPos = lightPos;
    this.focalPoint = focalPoint;
    this.lightUp = lightUp;
    this.hasShadowMap = hasShadowMap;
    this.fbo = new FBO(gl);
  }

  CalcLightMVP(translate, scale) {
    const model = mat4.create();
    const view = mat4.create();
    const projection = mat4.create();
    const mvp = mat4.create();
    // Model: translate, then scale, as MeshRender places the object.
    mat4.translate(model, model, translate);
    mat4.scale(model, model, scale);
    mat4.lookAt(view, this.lightPos, this.focalPoint, this.lightUp);
    const halfWidth = 100;
    const halfHeight = 80;
    mat4.ortho(projection, -halfWidth, halfWidth, -halfHeight, halfHeight, 0.01, 400);
    mat4.multiply(mvp, projection, view);
    mat4.multiply(mvp, mvp, model);
    return mvp;
  }
}
