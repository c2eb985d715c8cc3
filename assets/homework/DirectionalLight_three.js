// The framework's directional light with a CalcLightMVP of shadowlab's own writing in three.js
// (the framework's page loads lib/three.js before the student's code, so this is legal): an
// orthographic camera 200 world units wide, from 0.01 to 400 along its axis, at the light looking
// at its focal point; the same box as DirectionalLight.js, so the check should find nothing.
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
    const halfWidth = 100;
    const camera = new THREE.OrthographicCamera(-halfWidth, halfWidth, halfWidth, -halfWidth, 0.01, 400);
    camera.position.fromArray(this.lightPos);
    camera.up.fromArray(this.lightUp);
    camera.lookAt(new THREE.Vector3().fromArray(this.focalPoint));
    camera.updateMatrixWorld();
    // Model: translate, then scale, as MeshRender places the object.
    const model = new THREE.Matrix4().makeTranslation(translate[0], translate[1], translate[2]);
    model.multiply(new THREE.Matrix4().makeScale(scale[0], scale[1], scale[2]));
    const mvp = new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    mvp.multiply(model);
    return mvp.elements;
  }
}
