// shadowlab's own copy of the framework's interface: a program and its uniform locations by name.
class Shader {
    constructor(gl, vsSrc, fsSrc, shaderLocations) {
        this.gl = gl;
        const vs = this.compileShader(vsSrc, gl.VERTEX_SHADER);
        const fs = this.compileShader(fsSrc, gl.FRAGMENT_SHADER);
        this.program = this.addShaderLocations({ glShaderProgram: this.linkShader(vs, fs) }, shaderLocations);
    }

    compileShader(source, type) {
        const gl = this.gl;
        const shader = gl.createShader(type);
        gl.shaderSource(shader, source);
        gl.compileShader(shader);
        if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
            console.error('shader compiler error:\n' + gl.getShaderInfoLog(shader));
        }
        return shader;
    }

    linkShader(vs, fs) {
        const gl = this.gl;
        const program = gl.createProgram();
        gl.attachShader(program, vs);
        gl.attachShader(program, fs);
        gl.linkProgram(program);
        if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
            console.error('shader linker error:\n' + gl.getProgramInfoLog(program));
        }
        return program;
    }

    addShaderLocations(result, shaderLocations) {
        const gl = this.gl;
        result.uniforms = {};
        result.attribs = {};
        if (shaderLocations && shaderLocations.uniforms) {
            for (const name of shaderLocations.uniforms) {
                result.uniforms[name] = gl.getUniformLocation(result.glShaderProgram, name);
            }
        }
        if (shaderLocations && shaderLocations.attribs) {
            for (const name of shaderLocations.attribs) {
                result.attribs[name] = gl.getAttribLocation(result.glShaderProgram, name);
            }
        }
        return result;
    }
}
