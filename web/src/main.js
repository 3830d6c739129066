// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The baked world's viewer: the tileset beside this page (../tileset.json)
// drawn by 3d-tiles-renderer on three.js with Strata's own shading.
//
// URL parameters (a view can be shared and tested):
//   pos=X,Y,Z target=X,Y,Z fov=DEG  the camera (scene metres, y up; default: the scene's camera as `strata render DIR` frames it)
//   sse=PIXELS                      level of detail: the screen-space error target (default 2; 0 loads every level-0 tile)
//   view=NAME                       a debug view: shaded, weights, normals, metallic, occlusion, height, smoothness, albedo, layers
//   shadows=0                       sun shadows off (on where the scene has them)
//   controls=0                      no camera controls; ui=0: no text over the picture (tests)
//   tiles=0                         the sky alone (tests: which pixels are terrain)
// Keys: 0-8 debug views, Tab orbit/fly, W A S D Q E move (shift: 5x), H shadows flag.
// window.strataReady turns true once every tile the view needs is loaded and drawn;
// window.strataStats holds timings and counts.

import * as THREE from 'three';
import { TilesRenderer } from '3d-tiles-renderer';
import { GLTFExtensionsPlugin } from '3d-tiles-renderer/plugins';
import { MeshoptDecoder } from 'three/examples/jsm/libs/meshopt_decoder.module.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { DEBUG_VIEWS, loadMaps, makeUniforms, makeTerrainMaterial, makeSky, makeShadowPass, updateFrameUniforms } from './material.js';

const stats = { start: performance.now(), firstFrameMs: null, firstTileMs: null, mapsReadyMs: null, readyMs: null, tilesLoaded: 0, frames: 0 };
window.strataReady = false;
window.strataStats = stats;

function parseVec3( params, key ) {

	const text = params.get( key );
	if ( text === null ) return null;
	const v = text.split( ',' ).map( Number );
	if ( v.length !== 3 || v.some( x => ! Number.isFinite( x ) ) ) throw new Error( `URL parameter ${ key }=${ text }: expected X,Y,Z` );
	return new THREE.Vector3( ...v );

}

function status( text ) {

	const el = document.getElementById( 'status' );
	if ( el ) el.textContent = text;

}

async function main() {

	const params = new URLSearchParams( location.search );
	if ( params.get( 'ui' ) === '0' ) for ( const id of [ 'status', 'help' ] ) document.getElementById( id )?.remove();
	const base = new URL( '.', location.href );
	const response = await fetch( new URL( 'strata.json', base ) );
	if ( ! response.ok ) throw new Error( `strata.json: HTTP ${ response.status }` );
	const config = await response.json();

	THREE.ColorManagement.enabled = false; // the shaders write sRGB bytes themselves
	const renderer = new THREE.WebGLRenderer( { antialias: ( config.samples || 1 ) > 1, preserveDrawingBuffer: true } );
	renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
	renderer.setPixelRatio( 1 );
	renderer.setSize( window.innerWidth, window.innerHeight );
	renderer.autoClear = true;
	const c = config.clearColor.map( v => v <= 0.0031308 ? 12.92 * Math.max( v, 0 ) : 1.055 * Math.pow( Math.min( v, 1 ), 1 / 2.4 ) - 0.055 );
	renderer.setClearColor( new THREE.Color( c[ 0 ], c[ 1 ], c[ 2 ] ), 1 );
	document.body.appendChild( renderer.domElement );

	// The maps load while the tiles stream (nothing is drawn before both).
	const textures = [];
	let mapsReady = false;
	const uniforms = makeUniforms( config, textures );
	const material = makeTerrainMaterial( config, uniforms );
	const viewName = params.get( 'view' );
	if ( viewName !== null ) {

		const index = DEBUG_VIEWS.indexOf( viewName );
		if ( index < 0 ) throw new Error( `URL parameter view=${ viewName }: one of ${ DEBUG_VIEWS.join( ', ' ) }` );
		uniforms.uFrame.value.debugView = index;

	}
	let shadows = params.get( 'shadows' ) !== '0' && config.shadows !== false;

	const scene = new THREE.Scene();
	const sky = uniforms.uAtmosphere.value.enabled ? makeSky( uniforms ) : null;
	if ( sky ) scene.add( sky );
	const shadowPass = makeShadowPass( uniforms );
	let shadowDirty = true;
	let lastShadow = - Infinity;
	const dummyShadowMap = uniforms.uShadowMap.value;

	// The camera: URL, else the scene's (as `strata render DIR` frames the world).
	const bounds = config.bounds;
	const lo = new THREE.Vector3( ...( bounds ? bounds.min : [ 0, 0, 0 ] ) );
	const hi = new THREE.Vector3( ...( bounds ? bounds.max : [ 1, 1, 1 ] ) );
	const centre = lo.clone().add( hi ).multiplyScalar( 0.5 );
	const extent = hi.distanceTo( lo );
	const cam = config.camera || { position: [ centre.x, hi.y + extent, centre.z + extent ], target: centre.toArray(), up: [ 0, 1, 0 ], fov: 35, near: 0.1, far: 4 * extent };
	const camera = new THREE.PerspectiveCamera( Number( params.get( 'fov' ) || cam.fov ), window.innerWidth / window.innerHeight, cam.near, cam.far );
	const position = parseVec3( params, 'pos' );
	const target = parseVec3( params, 'target' );
	camera.position.set( ...cam.position );
	camera.up.set( ...cam.up );
	const lookAt = new THREE.Vector3( ...cam.target );
	if ( position || target ) {

		// snapshotCamera()'s rule for --camera-position/--camera-target
		if ( position ) camera.position.copy( position );
		if ( target ) lookAt.copy( target );
		const forward = lookAt.clone().sub( camera.position ).normalize();
		camera.up.set( ...( Math.abs( forward.y ) > 0.999 ? [ 0, 0, - 1 ] : [ 0, 1, 0 ] ) );
		camera.near = Math.max( 1e-3, extent * 1e-4 );
		camera.far = camera.position.distanceTo( centre ) + extent + 1;

	}
	camera.lookAt( lookAt );
	camera.updateProjectionMatrix();

	// The tiles: 3D Tiles is z-up with y-up glTF content; the group turns
	// the tileset's frame back into the scene's (y up).
	const tiles = new TilesRenderer( new URL( config.tileset || '../tileset.json', base ).href );
	tiles.registerPlugin( new GLTFExtensionsPlugin( { meshoptDecoder: MeshoptDecoder } ) );
	tiles.errorTarget = params.has( 'sse' ) ? Number( params.get( 'sse' ) ) : 2;
	// A georeferenced tileset (--georeference) has a root transform from its
	// east-north-up frame to the Earth's: undone, so the scene's metres stay
	// the frame here.
	const placeGroup = () => {

		const m = new THREE.Matrix4().makeRotationX( - Math.PI / 2 );
		const t = tiles.root && tiles.root.transform;
		if ( t ) m.multiply( new THREE.Matrix4().fromArray( t ).invert() );
		tiles.group.matrixAutoUpdate = false;
		tiles.group.matrix.copy( m );
		tiles.group.matrixWorldNeedsUpdate = true;

	};
	placeGroup();
	tiles.addEventListener( 'load-tileset', placeGroup );
	for ( const event of [ 'load-model', 'dispose-model', 'tile-visibility-change' ] ) tiles.addEventListener( event, () => {

		shadowDirty = true;

	} );
	tiles.setCamera( camera );
	tiles.setResolutionFromRenderer( camera, renderer );
	tiles.addEventListener( 'load-model', ( { scene: model } ) => {

		if ( stats.tilesLoaded ++ === 0 ) stats.firstTileMs = performance.now(); // since navigation start
		model.traverse( o => {

			if ( o.isMesh ) {

				o.material.dispose?.();
				o.material = material;
				o.frustumCulled = false; // the tiles renderer culls tiles; the shadow pass needs those outside the view

			}

		} );

	} );
	let loadErrors = 0;
	tiles.addEventListener( 'load-error', e => {

		loadErrors ++;
		console.error( 'tile failed to load:', e.url || '', e.error || '' );

	} );
	const showTiles = params.get( 'tiles' ) !== '0';
	if ( showTiles ) scene.add( tiles.group );
	// Compile the shaders while the maps and the first tiles load: with
	// KHR_parallel_shader_compile the GPU process builds them meanwhile, so
	// the first frame does not wait for them (seconds on software WebGL).
	const warm = new THREE.Scene();
	for ( const m of [ material, shadowPass && shadowPass.material ] ) if ( m ) warm.add( new THREE.Mesh( new THREE.BufferGeometry(), m ) );
	renderer.compileAsync( warm, camera, scene ).then( () => renderer.compileAsync( scene, camera ) ).catch( e => console.warn( 'shader warm-up:', e ) );

	let controls = null;
	if ( params.get( 'controls' ) !== '0' ) {

		controls = new OrbitControls( camera, renderer.domElement );
		controls.target.copy( lookAt );
		controls.update();

	}
	window.strataView = { camera, controls, tiles, uniforms }; // for the console and tests
	let fly = false;
	const keys = new Set();
	window.addEventListener( 'keydown', e => {

		if ( e.key >= '0' && e.key <= '8' ) uniforms.uFrame.value.debugView = Number( e.key );
		else if ( e.key === 'Tab' ) {

			fly = ! fly;
			if ( controls ) {

				controls.enabled = ! fly;
				if ( ! fly ) {

					// orbit again around the point ahead, at the old distance
					const ahead = new THREE.Vector3();
					camera.getWorldDirection( ahead );
					const distance = Math.max( camera.position.distanceTo( controls.target ), 1e-3 );
					controls.target.copy( camera.position ).addScaledVector( ahead, distance );
					controls.update();

				}

			}
			e.preventDefault();

		} else if ( e.key === 'h' || e.key === 'H' ) shadows = ! shadows;
		keys.add( e.key.toLowerCase() );

	} );
	window.addEventListener( 'keyup', e => keys.delete( e.key.toLowerCase() ) );
	// Fly mode: drag to look around (yaw about +Y, pitch within ±89°).
	let look = null;
	renderer.domElement.addEventListener( 'pointerdown', e => {

		if ( fly ) look = { x: e.clientX, y: e.clientY };

	} );
	window.addEventListener( 'pointerup', () => {

		look = null;

	} );
	window.addEventListener( 'pointermove', e => {

		if ( ! fly || ! look ) return;
		const euler = new THREE.Euler().setFromQuaternion( camera.quaternion, 'YXZ' );
		euler.y -= ( e.clientX - look.x ) * 0.004;
		euler.x = Math.max( - 1.55, Math.min( 1.55, euler.x - ( e.clientY - look.y ) * 0.004 ) );
		euler.z = 0;
		camera.quaternion.setFromEuler( euler );
		look = { x: e.clientX, y: e.clientY };
		viewChanged = true;

	} );
	window.addEventListener( 'resize', () => {

		camera.aspect = window.innerWidth / window.innerHeight;
		camera.updateProjectionMatrix();
		renderer.setSize( window.innerWidth, window.innerHeight );
		tiles.setResolutionFromRenderer( camera, renderer );

	} );

	const size = new THREE.Vector2();
	let last = performance.now();
	// Frames are drawn only when something changed: the view (controls,
	// keys, resize, debug view) at once; the drawn tiles while they stream
	// at most once a second, since a frame of the layered material can take
	// a second on software WebGL, while tiles.update() runs every animation
	// frame so that streaming never waits for drawing.
	let viewChanged = true;
	let tilesChanged = true;
	let lastRender = - Infinity;
	let quietSince = null;
	// The address bar follows the camera (pos, target, fov), so the view
	// can be shared by copying it.
	let shareTimer = null;
	const shareView = () => {

		clearTimeout( shareTimer );
		shareTimer = setTimeout( () => {

			const p = new URLSearchParams( location.search );
			const round = v => v.toArray().map( x => Number( x.toFixed( 3 ) ) ).join( ',' );
			p.set( 'pos', round( camera.position ) );
			p.set( 'target', round( controls.target ) );
			p.set( 'fov', String( camera.fov ) );
			history.replaceState( null, '', `?${ p.toString().replace( /%2C/g, ',' ) }` );

		}, 500 );

	};
	if ( controls ) controls.addEventListener( 'change', () => {

		viewChanged = true;
		shareView();

	} );
	window.addEventListener( 'keydown', () => {

		viewChanged = true;

	} );
	window.addEventListener( 'resize', () => {

		viewChanged = true;

	} );
	for ( const event of [ 'load-model', 'dispose-model', 'tile-visibility-change' ] ) tiles.addEventListener( event, () => {

		tilesChanged = true;

	} );
	function frame() {

		const now = performance.now();
		const dt = Math.min( 0.1, ( now - last ) / 1000 );
		last = now;
		if ( keys.size ) {

			const speed = extent * 0.2 * dt * ( keys.has( 'shift' ) ? 5 : 1 );
			const forward = new THREE.Vector3();
			camera.getWorldDirection( forward );
			const right = forward.clone().cross( camera.up ).normalize();
			const move = new THREE.Vector3();
			if ( keys.has( 'w' ) ) move.add( forward );
			if ( keys.has( 's' ) ) move.sub( forward );
			if ( keys.has( 'd' ) ) move.add( right );
			if ( keys.has( 'a' ) ) move.sub( right );
			if ( keys.has( 'e' ) ) move.y += 1;
			if ( keys.has( 'q' ) ) move.y -= 1;
			move.multiplyScalar( speed );
			camera.position.add( move );
			if ( controls ) {

				controls.target.add( move );
				shareView();

			}
			viewChanged = true;

		}
		if ( controls && controls.enabled ) controls.update();
		camera.updateMatrixWorld();
		if ( showTiles ) tiles.update();
		const busy = showTiles ? tiles.stats.downloading + tiles.stats.parsing + ( tiles.stats.queued || 0 ) : 0;
		const streaming = busy > 0;
		// The first tiles are drawn as soon as they arrive (no throttle before the first frame with terrain).
		const firstTiles = showTiles && stats.firstFrameMs === null;
		const render = mapsReady && ( stats.frames === 0 || viewChanged || ( tilesChanged && ( ! streaming || firstTiles || now - lastRender > 1000 ) ) );
		if ( render ) {

			viewChanged = false;
			tilesChanged = false;
			lastRender = now;
			renderer.getDrawingBufferSize( size );
			updateFrameUniforms( uniforms, camera, size.x, size.y );
			const shadowsOn = shadows && shadowPass !== null && showTiles;
			// The shadow map follows the drawn tiles; while they stream at
			// most every 2 s (a 2048² depth pass is slow on software WebGL).
			if ( shadowsOn && shadowDirty && ( ! streaming || now - lastShadow > 2000 ) ) {

				lastShadow = now;
				if ( sky ) sky.visible = false;
				scene.overrideMaterial = shadowPass.material;
				renderer.setRenderTarget( shadowPass.target );
				renderer.clear( false, true, false );
				renderer.render( scene, camera );
				renderer.setRenderTarget( null );
				scene.overrideMaterial = null;
				if ( sky ) sky.visible = true;
				shadowDirty = false;

			}
			if ( shadowsOn && shadowDirty ) tilesChanged = true; // draw again with the new map
			uniforms.uShadow.value.enabled = shadowsOn ? 1 : 0;
			uniforms.uShadowMap.value = shadowsOn ? shadowPass.depthTexture : dummyShadowMap;
			renderer.render( scene, camera );
			stats.frames ++;
			let drawn = 0;
			tiles.group.traverse( o => {

				if ( o.isMesh && o.visible ) drawn ++;

			} );
			stats.meshesDrawn = drawn;
			if ( stats.firstFrameMs === null && ( drawn > 0 || ! showTiles ) ) stats.firstFrameMs = performance.now(); // since navigation start

		}
		// Ready: nothing streaming or changed for 3 animation frames after a frame drew it all.
		const settled = stats.frames > 0 && ( ! showTiles || stats.tilesLoaded > 0 ) && ! streaming && ! render && ! tilesChanged && ! viewChanged;
		quietSince = settled ? ( quietSince ?? 0 ) + 1 : null;
		if ( ! window.strataReady && quietSince >= 3 ) {

			stats.readyMs = now; // since navigation start
			// The contents drawn, by level (tiles/L/...): what the view loaded.
			stats.visibleByLevel = {};
			for ( const tile of tiles.visibleTiles ) {

				const uri = tile.content && tile.content.uri || '';
				const m = /tiles\/(\d+)\//.exec( uri );
				const key = m ? m[ 1 ] : 'other';
				stats.visibleByLevel[ key ] = ( stats.visibleByLevel[ key ] || 0 ) + 1;

			}
			stats.loadErrors = loadErrors;
			window.strataReady = true;
			status( '' );

		}
		requestAnimationFrame( frame );

	}
	status( 'loading tiles…' );
	requestAnimationFrame( frame );
	const maps = await loadMaps( config, base, renderer );
	maps.forEach( ( t, i ) => {

		textures[ i ] = t;

	} );
	mapsReady = true;
	stats.mapsReadyMs = performance.now(); // since navigation start

}

main().catch( e => {

	console.error( 'strata viewer:', e && e.stack ? e.stack : e );
	status( `error: ${ e.message || e }` );
	window.strataError = String( e && e.message || e );

} );
