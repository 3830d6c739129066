// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Loads a `strata bake` folder in a real 3D Tiles client run headless in Node:
// the TilesRenderer of the npm package 3d-tiles-renderer (NASA-AMMOS/3DTilesRendererJS)
// on three.js, fed by a local http server, driven by a PerspectiveCamera at a few
// viewpoints until loading settles.
//
//   node tiles_client.mjs BAKE_DIR [--strict]
//
// Exits 0 when every viewpoint loads as expected; otherwise prints one line
// "tiles_client: FAIL: <reason>" and exits 1 (2 for usage, 3 when the npm packages
// cannot be imported). Checks:
//   * the root tileset.json is fetched and parsed by the client (load-root-tileset);
//   * no load-error event, no failed tile, no http 404, no console.error from the client;
//   * far view: at least one tile content (a glTF scene) loaded, none of level 0;
//   * near views (above a single-content leaf and above a `contents` leaf):
//     the level-0 content under the camera is loaded and visible;
//   * fine view (errorTarget 0, whole bake in view): every level-0 content loads.
//
// 3d-tiles-renderer (0.5.x) does not implement 3D Tiles 1.1 `contents` (several
// contents per tile): it ignores the array and treats such a tile as empty. Unless
// --strict is given, a small plugin in this file (MultipleContentsShim) loads every
// entry of a `contents` array through the client's own fetch and glTF parse path and
// shows them as the tile's one scene; with --strict, such tiles show nothing and the
// checks above fail.
//
// ES modules ignore NODE_PATH: bare imports that do not resolve from this file's folder
// are looked up in each NODE_PATH folder through the package's "exports" map.

import { createServer } from 'node:http';
import { readFile, stat } from 'node:fs/promises';
import { existsSync, readFileSync } from 'node:fs';
import { join, resolve, normalize, sep, delimiter } from 'node:path';
import { pathToFileURL } from 'node:url';

function fail( reason, code = 1 ) {

	console.log( `tiles_client: FAIL: ${ reason }` );
	process.exit( code );

}

// --- module resolution -------------------------------------------------------------------

async function importPackage( name, subpath = '.' ) {

	const spec = subpath === '.' ? name : `${ name }/${ subpath.replace( /^\.\//, '' ) }`;
	try {

		return await import( spec );

	} catch ( e ) {

		if ( e.code !== 'ERR_MODULE_NOT_FOUND' ) throw e;

	}

	for ( const dir of ( process.env.NODE_PATH || '' ).split( delimiter ).filter( Boolean ) ) {

		const pkgDir = join( dir, name );
		const pkgJson = join( pkgDir, 'package.json' );
		if ( ! existsSync( pkgJson ) ) continue;
		const pkg = JSON.parse( readFileSync( pkgJson, 'utf8' ) );
		let target = pkg.exports ? pkg.exports[ subpath ] : ( subpath === '.' ? ( pkg.module || pkg.main ) : subpath );
		if ( target && typeof target === 'object' ) target = target.import || target.default;
		// A file the exports map only covers by a wildcard ("./examples/jsm/*"): by its path.
		if ( typeof target !== 'string' && subpath !== '.' && existsSync( join( pkgDir, subpath ) ) ) target = subpath;
		if ( typeof target !== 'string' ) continue;
		return import( pathToFileURL( join( pkgDir, target ) ).href );

	}

	fail( `cannot import the npm package '${ spec }' (install 3d-tiles-renderer and three, ` +
		'then run from their node_modules or set NODE_PATH to it)', 3 );

}

// --- arguments and the tileset as written ------------------------------------------------

const args = process.argv.slice( 2 );
const strict = args.includes( '--strict' );
const positional = args.filter( a => ! a.startsWith( '--' ) );
if ( positional.length !== 1 ) fail( 'usage: node tiles_client.mjs BAKE_DIR [--strict]', 2 );
const bakeDir = resolve( positional[ 0 ] );
const tilesetPath = join( bakeDir, 'tileset.json' );
if ( ! existsSync( tilesetPath ) ) fail( `no tileset.json in ${ bakeDir }` );

let rawTileset;
let preError = null;
try {

	rawTileset = JSON.parse( readFileSync( tilesetPath, 'utf8' ) );

} catch ( e ) {

	preError = `tileset.json is not JSON: ${ e.message }`;

}

if ( ! preError && ( ! rawTileset || typeof rawTileset !== 'object' || ! rawTileset.root || ! rawTileset.asset ) ) {

	preError = 'tileset.json has no "asset" or no "root"';

}

// The browser APIs the client touches in Node: window.location (base of relative tileset
// URLs, set to the server's address below) and requestAnimationFrame (its schedulers).
// Nothing else is stubbed: the .glb contents carry no textures, so GLTFLoader needs no DOM.
globalThis.window = globalThis.window || { location: { href: 'http://127.0.0.1/' } };
globalThis.requestAnimationFrame = globalThis.requestAnimationFrame || ( cb => setTimeout( () => cb( performance.now() ), 16 ) );
globalThis.cancelAnimationFrame = globalThis.cancelAnimationFrame || ( h => clearTimeout( h ) );

const { TilesRenderer, LOADED, FAILED } = await importPackage( '3d-tiles-renderer' );
const THREE = await importPackage( 'three' );
// Bakes write compact tiles by default (EXT_meshopt_compression, KHR_mesh_quantization):
// a client decodes them with meshoptimizer's decoder, which three.js ships (WebAssembly,
// no worker), registered through the renderer's GLTFExtensionsPlugin as a web page does.
const { GLTFExtensionsPlugin } = await importPackage( '3d-tiles-renderer', './plugins' );
const { MeshoptDecoder } = await importPackage( 'three', './examples/jsm/libs/meshopt_decoder.module.js' );
await MeshoptDecoder.ready;
const { PerspectiveCamera, Group, Vector3 } = THREE;
const versionOf = name => {

	for ( const dir of [ join( process.cwd(), 'node_modules' ), ...( process.env.NODE_PATH || '' ).split( delimiter ).filter( Boolean ) ] ) {

		const p = join( dir, name, 'package.json' );
		if ( existsSync( p ) ) return JSON.parse( readFileSync( p, 'utf8' ) ).version;

	}

	return '?';

};

// --- a local http server for the bake folder ---------------------------------------------

const requests = [];
const notFound = [];
const server = createServer( async ( req, res ) => {

	// the bake is served under /bake/ (a tileset at the server root makes the client ask
	// for '//tiles/...': it joins its base path, which then ends in '/', with '/' + uri)
	const path = decodeURIComponent( req.url.split( /[?#]/ )[ 0 ] ).replace( /\/{2,}/g, '/' );
	const file = path.startsWith( '/bake/' ) ? normalize( join( bakeDir, path.slice( 6 ) ) ) : '';
	requests.push( path );
	try {

		if ( ! file.startsWith( bakeDir + sep ) || ! ( await stat( file ) ).isFile() ) throw new Error();
		const body = await readFile( file );
		const type = file.endsWith( '.json' ) ? 'application/json' : file.endsWith( '.glb' ) ? 'model/gltf-binary' : 'application/octet-stream';
		res.writeHead( 200, { 'Content-Type': type, 'Content-Length': body.length } );
		res.end( body );

	} catch {

		notFound.push( path );
		res.writeHead( 404 );
		res.end();

	}

} );
await new Promise( ok => server.listen( 0, '127.0.0.1', ok ) );
const baseUrl = `http://127.0.0.1:${ server.address().port }/bake/`;
globalThis.window.location.href = baseUrl;

// --- the client's errors -----------------------------------------------------------------

const clientErrors = [];
const consoleError = console.error;
console.error = ( ...a ) => {

	clientErrors.push( a.map( x => ( x && x.message ) || String( x ) ).join( ' ' ) );

};

const clientWarnings = new Set();
console.warn = ( ...a ) => clientWarnings.add( a.join( ' ' ) );
process.on( 'unhandledRejection', e => clientErrors.push( `unhandled rejection: ${ e && e.message || e }` ) );

const delay = ms => new Promise( ok => setTimeout( ok, ms ) );

// --- a tileset.json that is not one: what does the client make of it? ---------------------

if ( preError ) {

	const tiles = new TilesRenderer( baseUrl + 'tileset.json' );
	let clientError = null;
	tiles.addEventListener( 'load-error', e => clientError = e.error && e.error.message || String( e.error ) );
	const camera = new PerspectiveCamera();
	tiles.setCamera( camera );
	tiles.setResolution( camera, 1280, 720 );
	for ( let i = 0; i < 400 && tiles.rootLoadingState !== LOADED && tiles.rootLoadingState !== FAILED; i ++ ) {

		tiles.update();
		await delay( 5 );

	}

	server.close();
	fail( `${ preError }; the client ${ clientError ? `fails too: ${ clientError }` : tiles.root ? 'parsed the root anyway' : 'did not load it' }` );

}

const uriLevel = uri => {

	const m = /(?:^|\/)tiles\/(\d+)\//.exec( uri );
	return m ? Number( m[ 1 ] ) : - 1;

};

const contentUris = node => [
	...( node.content && node.content.uri ? [ node.content.uri ] : [] ),
	...( Array.isArray( node.contents ) ? node.contents.map( c => c.uri ) : [] ),
];

// Walk the tileset as written: leaves, multi-content nodes, the error scale of the
// nodes whose children hold level-0 contents, and that of content-less grouping nodes.
const leaves = [];
let multiContentNodes = 0;
let maxLeafParentError = 0;
let minGroupingError = Infinity;
let nodeCount = 0;
( function walk( node, parent ) {

	nodeCount ++;
	const uris = contentUris( node );
	if ( Array.isArray( node.contents ) ) multiContentNodes ++;
	const children = node.children || [];
	if ( uris.length === 0 && children.length > 0 ) minGroupingError = Math.min( minGroupingError, node.geometricError );
	if ( children.length === 0 && uris.length > 0 ) {

		leaves.push( { node, uris, multi: Array.isArray( node.contents ), parentError: parent ? parent.geometricError : Infinity } );
		if ( parent ) maxLeafParentError = Math.max( maxLeafParentError, parent.geometricError );

	}

	children.forEach( c => walk( c, node ) );

} )( rawTileset.root, null );
if ( leaves.length === 0 ) fail( 'the tileset has no leaf with content' );
const leafUris = leaves.flatMap( l => l.uris );

// --- 3D Tiles 1.1 `contents` for a client without it ---------------------------------------

class MultipleContentsShim {

	constructor( onContent ) {

		this.name = 'STRATA_TEST_MULTIPLE_CONTENTS_SHIM';
		this.onContent = onContent;
		this.rewritten = 0;

	}

	init( tiles ) {

		this.tiles = tiles;

	}

	// tileset JSON: a node with `contents` [a, b, ...] gets `content` {uri: a}; the rest
	// are loaded in parseTile.
	fetchData( url, options ) {

		if ( ! /\.json(\?|#|$)/.test( url ) ) return null;
		return fetch( url, options ).then( async res => {

			if ( ! res.ok ) return res;
			const json = await res.json();
			const rewrite = node => {

				if ( Array.isArray( node.contents ) && ! node.content && node.contents.length > 0 ) {

					node.content = { uri: node.contents[ 0 ].uri };
					node.strataExtraContents = node.contents.slice( 1 ).map( c => c.uri );
					this.rewritten ++;

				}

				( node.children || [] ).forEach( rewrite );

			};

			if ( json.root ) rewrite( json.root );
			return new Response( JSON.stringify( json ), { status: 200, headers: { 'Content-Type': 'application/json' } } );

		} );

	}

	parseTile( buffer, tile, extension, url, signal ) {

		if ( ! tile.strataExtraContents ) return null;
		const tiles = this.tiles;
		return ( async () => {

			const holders = [ { buffer, url } ];
			for ( const uri of tile.strataExtraContents ) {

				const u = new URL( uri, tile.internal.basePath + '/' ).toString();
				const res = await tiles.fetchData( u, { ...tiles.fetchOptions, signal } );
				if ( ! res.ok ) throw new Error( `Failed to load model with error code ${ res.status } (${ u })` );
				holders.push( { buffer: await res.arrayBuffer(), url: u } );

			}

			const group = new Group();
			const data = { materials: [], geometry: [], textures: [] };
			for ( const h of holders ) {

				// the client's own parse path (GLTFLoader, y-up to z-up, tile transform)
				const part = { ...tile, engineData: { transform: tile.engineData.transform } };
				await tiles.parseTile( h.buffer, part, getExt( h.url ), h.url, signal );
				if ( signal.aborted || ! part.engineData.scene ) return;
				part.engineData.scene.traverse( c => {

					c.userData.tile = tile;

				} );
				group.add( part.engineData.scene );
				data.materials.push( ...part.engineData.materials );
				data.geometry.push( ...part.engineData.geometry );
				data.textures.push( ...part.engineData.textures );
				if ( h.url !== url ) this.onContent( h.url );

			}

			Object.assign( tile.engineData, data, { scene: group, metadata: null } );

		} )();

	}

}

const getExt = url => ( /\.([a-z0-9]+)(?:[?#]|$)/i.exec( url ) || [] )[ 1 ] || null;

// --- viewpoints ----------------------------------------------------------------------------

const WIDTH = 1280, HEIGHT = 720, FOV = 60;
const sseDenominator = 2 * Math.tan( FOV * Math.PI / 360 ) / HEIGHT;
const ERROR_TARGET = 16;

const boxOf = node => {

	const b = node.boundingVolume && node.boundingVolume.box;
	if ( ! b ) fail( 'a node has no box bounding volume' );
	const half = new Vector3(
		Math.hypot( b[ 3 ], b[ 4 ], b[ 5 ] ), Math.hypot( b[ 6 ], b[ 7 ], b[ 8 ] ), Math.hypot( b[ 9 ], b[ 10 ], b[ 11 ] ) );
	return { center: new Vector3( b[ 0 ], b[ 1 ], b[ 2 ] ), half };

};

const rootBox = boxOf( rawTileset.root );
const rootRadius = Math.hypot( rootBox.half.x, rootBox.half.y );
// far enough that the parents of level-0 leaves do not refine (half the error target),
// near enough that the content-less grouping nodes above them do.
const farDistance = Math.max( 3 * rootRadius, 2 * maxLeafParentError / ( sseDenominator * ERROR_TARGET ) );
const far = {
	name: 'far',
	position: rootBox.center.clone().add( new Vector3( 0, - 0.3 * farDistance, rootBox.half.z + farDistance ) ),
	target: rootBox.center.clone(),
	expect: 'coarse',
};
if ( Number.isFinite( minGroupingError ) && minGroupingError / ( farDistance * 1.5 * sseDenominator ) <= ERROR_TARGET ) {

	console.log( `tiles_client: note: grouping nodes (geometricError ${ minGroupingError.toFixed( 2 ) }) may not refine at the far distance ${ farDistance.toFixed( 1 ) } m` );

}

const nearOver = ( leaf, name ) => {

	const box = boxOf( leaf.node );
	// a quarter of the distance below which the leaf's parent must refine, at most a
	// quarter of the tile's width
	const lift = Math.max( 0.01, Math.min( 0.25 * Math.min( box.half.x, box.half.y ),
		0.25 * leaf.parentError / ( sseDenominator * ERROR_TARGET ) ) );
	return {
		name,
		position: box.center.clone().add( new Vector3( 0, - 0.2 * lift, box.half.z + lift ) ),
		target: box.center.clone(),
		expect: 'fine',
		leaf,
	};

};

const singleLeaf = leaves.find( l => ! l.multi );
const multiLeaf = leaves.find( l => l.multi );
const viewpoints = [ far ];
if ( singleLeaf ) viewpoints.push( nearOver( singleLeaf, `near ${ singleLeaf.uris[ 0 ] }` ) );
if ( multiLeaf ) viewpoints.push( nearOver( multiLeaf, `near ${ multiLeaf.uris.join( '+' ) } (contents)` ) );
viewpoints.push( { ...far, name: 'fine (errorTarget 0)', expect: 'all-leaves', errorTarget: 0 } );

// --- run the client ----------------------------------------------------------------------

// A loaded content must hold triangles, and once the client has placed it (glTF y-up
// turned to the tileset's z-up, tile transform) lie inside its tile's bounding box.
const { Box3 } = THREE;
let trianglesLoaded = 0;
let worstOutside = 0;
function checkPlacement( scene, tile, uri, events ) {

	let triangles = 0;
	scene.updateMatrixWorld( true );
	scene.traverse( c => {

		if ( ! c.isMesh ) return;
		const g = c.geometry;
		if ( ! g.attributes.position ) return;
		triangles += ( g.index ? g.index.count : g.attributes.position.count ) / 3;

	} );
	trianglesLoaded += triangles;
	if ( triangles === 0 ) {

		events.errors.push( `content check: ${ uri }: the glTF scene has no triangles` );
		return;

	}

	const b = tile.boundingVolume.box;
	if ( ! b || b[ 4 ] || b[ 5 ] || b[ 6 ] || b[ 8 ] || b[ 9 ] || b[ 10 ] ) return; // only axis-aligned boxes
	const tileBox = new Box3(
		new Vector3( b[ 0 ] - Math.abs( b[ 3 ] ), b[ 1 ] - Math.abs( b[ 7 ] ), b[ 2 ] - Math.abs( b[ 11 ] ) ),
		new Vector3( b[ 0 ] + Math.abs( b[ 3 ] ), b[ 1 ] + Math.abs( b[ 7 ] ), b[ 2 ] + Math.abs( b[ 11 ] ) ) );
	const box = new Box3().setFromObject( scene );
	const outside = Math.max(
		tileBox.min.x - box.min.x, tileBox.min.y - box.min.y, tileBox.min.z - box.min.z,
		box.max.x - tileBox.max.x, box.max.y - tileBox.max.y, box.max.z - tileBox.max.z );
	worstOutside = Math.max( worstOutside, outside );
	const size = new Vector3();
	tileBox.getSize( size );
	if ( outside > 0.01 * Math.max( size.x, size.y, size.z ) + 1e-3 ) {

		const f = v => v.toArray().map( x => x.toFixed( 2 ) ).join( ',' );
		events.errors.push( `content check: ${ uri }: the placed content (${ f( box.min ) } .. ${ f( box.max ) }) sticks out of its box ` +
			`(${ f( tileBox.min ) } .. ${ f( tileBox.max ) }) by ${ outside.toFixed( 3 ) } m` );

	}

}


async function runViewpoint( vp ) {

	const loaded = new Set();
	const events = { rootLoaded: false, errors: [] };
	const tiles = new TilesRenderer( baseUrl + 'tileset.json' );
	tiles.registerPlugin( new GLTFExtensionsPlugin( { meshoptDecoder: MeshoptDecoder } ) );
	let shim = null;
	if ( ! strict ) {

		shim = new MultipleContentsShim( u => loaded.add( u.slice( baseUrl.length ) ) );
		tiles.registerPlugin( shim );

	}

	tiles.errorTarget = vp.errorTarget ?? ERROR_TARGET;
	tiles.lruCache.minSize = 0;
	tiles.lruCache.maxSize = Math.max( 800, 4 * nodeCount );
	tiles.addEventListener( 'load-root-tileset', () => {

		events.rootLoaded = true;

	} );
	tiles.addEventListener( 'load-model', e => {

		loaded.add( e.url.slice( baseUrl.length ) );
		checkPlacement( e.scene, e.tile, e.url.slice( baseUrl.length ), events );

	} );
	tiles.addEventListener( 'load-error', e => events.errors.push( `load error: ${ e.url }: ${ e.error && e.error.message || e.error }` ) );

	const camera = new PerspectiveCamera( FOV, WIDTH / HEIGHT, 0.1, 10 * ( farDistance + rootRadius + rootBox.half.z ) );
	camera.up.set( 0, 0, 1 );
	camera.position.copy( vp.position );
	camera.lookAt( vp.target );
	camera.updateMatrixWorld( true );
	tiles.setCamera( camera );
	tiles.setResolution( camera, WIDTH, HEIGHT );
	tiles.group.updateMatrixWorld( true );

	// update until the root is in, nothing is queued, downloading or parsing, for a few frames
	const started = Date.now();
	let quiet = 0;
	let frames = 0;
	while ( quiet < 5 ) {

		tiles.update();
		frames ++;
		await delay( 5 );
		if ( tiles.rootLoadingState === FAILED || events.errors.length ) break;
		const s = tiles.stats;
		const busy = ! tiles.root || tiles.isLoading || s.queued || s.downloading || s.parsing || tiles.loadingTiles.size;
		quiet = busy ? 0 : quiet + 1;
		if ( Date.now() - started > 120000 ) fail( `${ vp.name }: loading did not settle within 120 s (stats ${ JSON.stringify( tiles.stats ) })` );

	}

	const visible = [ ...tiles.visibleTiles ].flatMap( t => [ t.content.uri, ...( t.strataExtraContents || [] ) ] );
	const result = { loaded: [ ...loaded ].sort(), visible: visible.sort(), events, stats: { ...tiles.stats }, frames, shimmed: shim ? shim.rewritten : 0 };
	tiles.dispose();
	return result;

}

const problems = [];
let sawMultiRewrite = 0;
console.log( `tiles_client: 3d-tiles-renderer ${ versionOf( '3d-tiles-renderer' ) }, three ${ versionOf( 'three' ) }, node ${ process.version }; ` +
	`${ bakeDir }: ${ nodeCount } nodes, ${ leaves.length } leaves, ${ multiContentNodes } with \`contents\`` +
	( strict ? ', strict (no `contents` shim)' : '' ) );
const union = new Set();
for ( const vp of viewpoints ) {

	const r = await runViewpoint( vp );
	sawMultiRewrite = Math.max( sawMultiRewrite, r.shimmed );
	r.loaded.forEach( u => union.add( u ) );
	const byLevel = {};
	r.loaded.forEach( u => byLevel[ uriLevel( u ) ] = ( byLevel[ uriLevel( u ) ] || 0 ) + 1 );
	const levels = Object.keys( byLevel ).sort().map( l => `L${ l }:${ byLevel[ l ] }` ).join( ' ' ) || 'none';
	console.log( `tiles_client: [${ vp.name }] camera (${ vp.position.toArray().map( v => v.toFixed( 1 ) ).join( ', ' ) }): ` +
		`loaded ${ r.loaded.length } contents (${ levels }), ${ r.visible.length } visible, ${ r.frames } updates` );
	if ( r.loaded.length <= 12 ) console.log( `tiles_client:   loaded: ${ r.loaded.join( ' ' ) }` );

	const p = msg => problems.push( `[${ vp.name }] ${ msg }` );
	if ( ! r.events.rootLoaded ) p( 'the client did not load the root tileset' );
	if ( r.events.errors.length ) p( r.events.errors[ 0 ] );
	if ( r.stats.failed ) p( `${ r.stats.failed } tiles failed to load` );
	if ( r.loaded.length === 0 ) p( 'no tile content loaded' );
	if ( r.visible.length === 0 ) p( 'no tile content visible' );
	if ( vp.expect === 'coarse' && byLevel[ 0 ] ) p( `loaded level-0 content from far away: ${ r.loaded.filter( u => uriLevel( u ) === 0 ).slice( 0, 3 ).join( ' ' ) }` );
	if ( vp.expect === 'fine' ) {

		if ( ! byLevel[ 0 ] ) p( 'loaded no level-0 content near a tile' );
		for ( const u of vp.leaf.uris ) {

			if ( ! r.loaded.includes( u ) ) p( `did not load the level-0 content under the camera: ${ u }` );
			else if ( ! r.visible.includes( u ) ) p( `loaded but did not show the level-0 content under the camera: ${ u }` );

		}

	}

	if ( vp.expect === 'all-leaves' ) {

		const missing = leafUris.filter( u => ! r.loaded.includes( u ) );
		if ( missing.length ) p( `${ missing.length } of ${ leafUris.length } level-0 contents not loaded, e.g. ${ missing[ 0 ] }` );

	}

	if ( problems.length ) break;

}

server.close();
console.error = consoleError;
clientWarnings.forEach( w => console.log( `tiles_client: client warning: ${ w }` ) );
if ( notFound.length ) problems.unshift( `http 404 for ${ notFound.length } requests, e.g. ${ notFound[ 0 ] }` );
if ( clientErrors.length && ! problems.length ) problems.push( `the client logged an error: ${ clientErrors[ 0 ] }` );
if ( problems.length ) {

	const hint = strict && multiContentNodes
		? ` (3d-tiles-renderer ignores 3D Tiles 1.1 \`contents\`; ${ multiContentNodes } nodes use it)` : '';
	clientErrors.slice( 0, 6 ).forEach( e => console.log( `tiles_client:   client error: ${ e.replace( /\s+/g, ' ' ) }` ) );
	fail( problems[ 0 ].replace( /\s+/g, ' ' ) + hint );

}

console.log( `tiles_client: OK: ${ viewpoints.length } viewpoints, ${ union.size } distinct contents loaded over ${ requests.length } http requests, ` +
	`${ trianglesLoaded } triangles placed inside their boxes (worst overshoot ${ worstOutside.toExponential( 1 ) } m)` +
	( sawMultiRewrite ? `; ${ sawMultiRewrite } \`contents\` nodes loaded through the test's shim (3d-tiles-renderer ignores \`contents\`)` : '' ) );
process.exit( 0 );
