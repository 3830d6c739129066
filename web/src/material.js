// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Strata's terrain material and sky in three.js: the GLSL ES programs
// generated from shaders/ at build time (web/GenerateShaders.cmake) with the
// uniform values and maps the bake wrote (viewer/strata.json, maps/*.png),
// set as the GL renderer sets them (render/src/GlRenderer.cpp).

import * as THREE from 'three';
import { TERRAIN_VERT, TERRAIN_FRAG, FULLSCREEN_VERT, SKY_FRAG, SHADOW_DEPTH_FRAG } from 'strata:shaders';
import { decodePng } from './png.js';

/** Debug views by name (DEBUG_VIEW_* of shaders/TriplanarMaterial.h). */
export const DEBUG_VIEWS = [ 'shaded', 'weights', 'normals', 'metallic', 'occlusion', 'height', 'smoothness', 'albedo', 'layers' ];

/** Sets value at a GLSL uniform path ("uLighting.lights[1].color") in nested objects/arrays. */
function setPath( root, path, value ) {

	const keys = [];
	for ( const part of path.split( '.' ) ) {

		const m = /^(\w+)((?:\[\d+\])*)$/.exec( part );
		if ( ! m ) throw new Error( `strata.json: bad uniform name '${ path }'` );
		keys.push( m[ 1 ] );
		for ( const index of m[ 2 ].matchAll( /\[(\d+)\]/g ) ) keys.push( Number( index[ 1 ] ) );

	}
	let node = root;
	for ( let i = 0; i < keys.length - 1; i ++ ) {

		if ( node[ keys[ i ] ] === undefined ) node[ keys[ i ] ] = typeof keys[ i + 1 ] === 'number' ? [] : {};
		node = node[ keys[ i ] ];

	}
	node[ keys[ keys.length - 1 ] ] = value;

}

/** Loads maps/*.png as the nine texture arrays, with the bake's own mip levels. */
export async function loadMaps( config, baseUrl, renderer ) {

	const files = new Map();
	for ( const map of config.maps ) {

		if ( ! files.has( map.file ) ) {

			files.set( map.file, fetch( new URL( map.file, baseUrl ) ).then( r => {

				if ( ! r.ok ) throw new Error( `${ map.file }: HTTP ${ r.status }` );
				return r.arrayBuffer();

			} ).then( b => decodePng( b, map.file ) ) );

		}

	}
	const gl = renderer.getContext();
	const textures = [];
	for ( const map of config.maps ) {

		const image = await files.get( map.file );
		const [ width, height ] = map.levels[ 0 ];
		const chain = map.levels.reduce( ( n, l ) => n + l[ 1 ], 0 );
		// Level l of layer i: rows from i * chain + (heights of the levels before l).
		const level = ( l, layers ) => {

			const [ w, h ] = map.levels[ l ];
			let first = 0;
			for ( let k = 0; k < l; k ++ ) first += map.levels[ k ][ 1 ];
			const out = new Uint8Array( w * h * 4 * layers );
			for ( let i = 0; i < layers; i ++ )
				for ( let y = 0; y < h; y ++ ) {

					const src = ( ( i * chain + first + y ) * image.width ) * 4;
					out.set( image.data.subarray( src, src + w * 4 ), ( i * h + y ) * w * 4 );

				}
			return out;

		};
		const texture = new THREE.DataArrayTexture( level( 0, map.layers ), width, height, map.layers );
		texture.format = THREE.RGBAFormat;
		texture.type = THREE.UnsignedByteType;
		texture.internalFormat = map.srgb ? 'SRGB8_ALPHA8' : 'RGBA8';
		texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
		texture.magFilter = THREE.LinearFilter;
		const mipmapped = map.levels.length > 1;
		texture.minFilter = ! mipmapped ? THREE.LinearFilter
			: config.filter === 'bilinear' ? THREE.LinearMipmapNearestFilter : THREE.LinearMipmapLinearFilter;
		texture.anisotropy = Math.max( 1, Math.min( config.anisotropy || 1, renderer.capabilities.getMaxAnisotropy() ) );
		// three.js allocates the whole chain and generates it; the bake's own
		// levels (box filtered in linear light, normals renormalised, detail
		// faded) then replace the generated ones.
		texture.generateMipmaps = mipmapped;
		texture.needsUpdate = true;
		renderer.initTexture( texture );
		if ( mipmapped ) {

			const glTexture = renderer.properties.get( texture ).__webglTexture;
			renderer.state.bindTexture( gl.TEXTURE_2D_ARRAY, glTexture );
			gl.pixelStorei( gl.UNPACK_FLIP_Y_WEBGL, false );
			gl.pixelStorei( gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false );
			gl.pixelStorei( gl.UNPACK_ALIGNMENT, 4 );
			for ( let l = 1; l < map.levels.length; l ++ ) {

				const [ w, h ] = map.levels[ l ];
				gl.texSubImage3D( gl.TEXTURE_2D_ARRAY, l, 0, 0, 0, w, h, map.layers, gl.RGBA, gl.UNSIGNED_BYTE, level( l, map.layers ) );

			}
			renderer.state.unbindTexture();

		}
		textures[ map.slot ] = texture;

	}
	return textures;

}

/** The shared uniform objects of the terrain and sky programs, filled from strata.json. */
export function makeUniforms( config, textures ) {

	const values = {
		uFrame: {
			viewProjection: new THREE.Matrix4(), cameraPosition: new THREE.Vector4(), textureOffset: [ 0, 0, 0, 0 ],
			wireColor: [ 0, 0, 0, 1 ], mapScale: 1, debugView: 0, wireframePass: 0,
			// The level of detail computed in the shader as the CPU reference does
			// (terrain.frag mapLod) unless anisotropic filtering needs the GPU's own.
			explicitLod: ( config.anisotropy || 1 ) > 1 ? 0 : 1,
			detailOffset: [ 0, 0, 0, 0 ], tileOffset: [ 0, 0, 0, 0 ],
		},
		uAtmosphere: {
			skyRayMatrix: new THREE.Matrix4(), viewportSize: new THREE.Vector2( 1, 1 ),
			padding0: 0, padding1: 0, padding2: 0,
		},
		uShadow: {
			lightViewProjection: new THREE.Matrix4(), lightDirection: [ 0, 1, 0 ], texelSize: 1, normalBias: 0,
			depthBias: 0, resolution: 1, enabled: 0,
		},
	};
	for ( const [ name, u ] of Object.entries( config.uniforms ) ) setPath( values, name, u.value );
	const shadowMap = new THREE.DataTexture( new Float32Array( 4 ), 1, 1, THREE.RGBAFormat, THREE.FloatType );
	shadowMap.needsUpdate = true;
	const uniforms = { uWorldOrigin: { value: new THREE.Vector3( ...config.origin ) }, uMaps: { value: textures }, uShadowMap: { value: shadowMap } };
	for ( const [ name, value ] of Object.entries( values ) ) uniforms[ name ] = { value };
	return uniforms;

}

/** The terrain program for the bake's feature set. */
export function makeTerrainMaterial( config, uniforms ) {

	const defines = { STRATA_FEATURES: `${ config.features }u` };
	if ( config.features & 1024 ) {

		defines.STRATA_LAYERED = 1;
		defines.STRATA_LAYER_COUNT = config.layerCount;

	}
	return new THREE.RawShaderMaterial( {
		name: 'strata-terrain', glslVersion: THREE.GLSL3, vertexShader: TERRAIN_VERT, fragmentShader: TERRAIN_FRAG,
		defines, uniforms, side: THREE.FrontSide,
	} );

}

/** The sky pass (sky.frag over one triangle covering the viewport), drawn first. */
export function makeSky( uniforms ) {

	const geometry = new THREE.BufferGeometry();
	geometry.setAttribute( 'position', new THREE.Float32BufferAttribute( new Float32Array( 9 ), 3 ) );
	const material = new THREE.RawShaderMaterial( {
		name: 'strata-sky', glslVersion: THREE.GLSL3, vertexShader: FULLSCREEN_VERT, fragmentShader: SKY_FRAG,
		uniforms: { uAtmosphere: uniforms.uAtmosphere }, depthTest: false, depthWrite: false,
	} );
	const mesh = new THREE.Mesh( geometry, material );
	mesh.frustumCulled = false;
	mesh.renderOrder = - 1;
	return mesh;

}

/**
 * The sun's shadow map (shaders/Shadow.h, step 1) as the GL renderer draws it:
 * the terrain vertex stage with the sun's view-projection, both windings,
 * depth GL_LESS into a 32-bit float depth texture cleared to 1, read texel
 * by texel by the terrain program. Null when the bake's scene has shadows off.
 */
export function makeShadowPass( uniforms ) {

	const shadow = uniforms.uShadow.value;
	if ( ! shadow.enabled ) return null;
	const resolution = shadow.resolution;
	const depthTexture = new THREE.DepthTexture( resolution, resolution, THREE.FloatType );
	depthTexture.minFilter = depthTexture.magFilter = THREE.NearestFilter;
	const target = new THREE.WebGLRenderTarget( resolution, resolution, { depthTexture, depthBuffer: true } );
	const frame = { ...uniforms.uFrame.value, viewProjection: new THREE.Matrix4().fromArray( shadow.lightViewProjection ) };
	const material = new THREE.RawShaderMaterial( {
		name: 'strata-shadow-depth', glslVersion: THREE.GLSL3, vertexShader: TERRAIN_VERT, fragmentShader: SHADOW_DEPTH_FRAG,
		uniforms: { uFrame: { value: frame }, uWorldOrigin: uniforms.uWorldOrigin }, side: THREE.DoubleSide,
		depthFunc: THREE.LessDepth, colorWrite: false,
	} );
	return { target, material, depthTexture };

}

const _rotation = new THREE.Matrix4();
const _rayToClip = new THREE.Matrix4();

/** Per frame: the camera-dependent uniforms, as GlRenderer::draw() and makeAtmosphereParams() set them. */
export function updateFrameUniforms( uniforms, camera, width, height ) {

	const frame = uniforms.uFrame.value;
	const origin = uniforms.uWorldOrigin.value;
	// view relative to the world origin (0 in this viewer's frame)
	const view = camera.matrixWorldInverse.clone();
	view.multiply( new THREE.Matrix4().makeTranslation( origin.x, origin.y, origin.z ) );
	frame.viewProjection.multiplyMatrices( camera.projectionMatrix, view );
	frame.cameraPosition.set( camera.position.x - origin.x, camera.position.y - origin.y, camera.position.z - origin.z, 1 );
	const a = uniforms.uAtmosphere.value;
	_rotation.extractRotation( camera.matrixWorldInverse );
	_rayToClip.multiplyMatrices( camera.projectionMatrix, _rotation );
	a.skyRayMatrix.copy( _rayToClip ).invert();
	a.viewportSize.set( width, height );

}
