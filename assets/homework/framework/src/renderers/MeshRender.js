// shadowlab's own copy of the framework's interface: one mesh drawn with one material: the
// model, view and projection matrices, then each of the material's uniforms by its type.
class MeshRender {
    #vertexBuffer;
    #normalBuffer;
    #texcoordBuffer;
    #indicesBuffer;

    constructor(gl, mesh, material) {
        this.gl = gl;
        this.mesh = mesh;
        this.material = material;
        this.#vertexBuffer = gl.createBuffer();
        this.#normalBuffer = gl.createBuffer();
        this.#texcoordBuffer = gl.createBuffer();
        this.#indicesBuffer = gl.createBuffer();
        const extraAttribs = [];
        if (mesh.hasVertices) {
            extraAttribs.push(mesh.vertexName);
            gl.bindBuffer(gl.ARRAY_BUFFER, this.#vertexBuffer);
            gl.bufferData(gl.ARRAY_BUFFER, mesh.vertices, gl.STATIC_DRAW);
        }
        if (mesh.hasNormals) {
            extraAttribs.push(mesh.normalName);
            gl.bindBuffer(gl.ARRAY_BUFFER, this.#normalBuffer);
            gl.bufferData(gl.ARRAY_BUFFER, mesh.normals, gl.STATIC_DRAW);
        }
        if (mesh.hasTexcoords) {
            extraAttribs.push(mesh.texcoordName);
            gl.bindBuffer(gl.ARRAY_BUFFER, this.#texcoordBuffer);
            gl.bufferData(gl.ARRAY_BUFFER, mesh.texcoords, gl.STATIC_DRAW);
        }
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#indicesBuffer);
        gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(mesh.indices), gl.STATIC_DRAW);
        this.material.setMeshAttribs(extraAttribs);
        this.shader = this.material.compile(gl);
    }

    bindCameraParameters(camera) {
        const gl = this.gl;
        const modelMatrix = mat4.create();
        const viewMatrix = mat4.create();
        const projectionMatrix = mat4.create();
        mat4.identity(modelMatrix);
        mat4.translate(modelMatrix, modelMatrix, this.mesh.transform.translate);
        mat4.scale(modelMatrix, modelMatrix, this.mesh.transform.scale);
        camera.updateMatrixWorld();
        mat4.invert(viewMatrix, camera.matrixWorld.elements);
        mat4.copy(projectionMatrix, camera.projectionMatrix.elements);
        const u = this.shader.program.uniforms;
        gl.uniformMatrix4fv(u.uProjectionMatrix, false, projectionMatrix);
        gl.uniformMatrix4fv(u.uModelMatrix, false, modelMatrix);
        gl.uniformMatrix4fv(u.uViewMatrix, false, viewMatrix);
        gl.uniform3fv(u.uCameraPos, [camera.position.x, camera.position.y, camera.position.z]);
    }

    bindMaterialParameters() {
        const gl = this.gl;
        let textureNum = 0;
        for (const name in this.material.uniforms) {
            const { type, value } = this.material.uniforms[name];
            const location = this.shader.program.uniforms[name];
            if (type === 'matrix4fv') gl.uniformMatrix4fv(location, false, value);
            else if (type === '3fv') gl.uniform3fv(location, value);
            else if (type === '1f') gl.uniform1f(location, value);
            else if (type === '1i') gl.uniform1i(location, value);
            else if (type === 'texture') {
                gl.activeTexture(gl.TEXTURE0 + textureNum);
                gl.bindTexture(gl.TEXTURE_2D, value && value.texture);
                gl.uniform1i(location, textureNum);
                textureNum += 1;
            }
        }
    }

    bindAttribute(buffer, name, size) {
        const gl = this.gl;
        const location = this.shader.program.attribs[name];
        gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
        gl.vertexAttribPointer(location, size, gl.FLOAT, false, 0, 0);
        gl.enableVertexAttribArray(location);
    }

    draw(camera) {
        const gl = this.gl;
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.material.frameBuffer || null);
        gl.useProgram(this.shader.program.glShaderProgram);
        if (this.mesh.hasVertices) this.bindAttribute(this.#vertexBuffer, this.mesh.vertexName, 3);
        if (this.mesh.hasNormals) this.bindAttribute(this.#normalBuffer, this.mesh.normalName, 3);
        if (this.mesh.hasTexcoords) this.bindAttribute(this.#texcoordBuffer, this.mesh.texcoordName, 2);
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#indicesBuffer);
        this.bindCameraParameters(camera);
        this.bindMaterialParameters();
        gl.drawElements(gl.TRIANGLES, this.mesh.count, gl.UNSIGNED_SHORT, 0);
    }
}
