// `baker view` end to end: a page written for the bundled room (ad-ycocg, the scene found beside
// the volume) opened in Debian's headless Chromium (SwiftShader WebGL 2). The colour at three
// probes' sphere centres, after undoing the page's display transform (sRGB of E/π · exposure),
// must be baker sample's irradiance at that probe for the normal facing the camera within 2 %;
// the probe-state toggle must recolour a relocated probe; a click prints baker sample's six
// axis values; no console error. --serve serves the same files. A damaged volume writes no page.
// A screenshot of the page is saved to SCREENSHOT when given.
// argv: node viewer.test.mjs BAKER SOURCE_DIR [SCREENSHOT]
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { bake, baker, check, finish, freshDirectory, runBaker, sample, sourceDir } from './support.mjs';
import { openPage, serve } from './browser.mjs';

const screenshot = process.argv[ 4 ] && path.resolve( process.argv[ 4 ] );
const dir = freshDirectory( 'viewer' );
for ( const file of [ 'default_room.gltf', 'default_room.bin' ] ) fs.copyFileSync( path.join( sourceDir, 'data/default_room', file ), path.join( dir, file ) );
bake( [ 'default_room.gltf', '--basis', 'ad-ycocg', '--rays', '256', '--spacing', '1', '--seed', '1', '--out', 'room.vdb' ], dir );
const written = runBaker( [ 'view', 'room.vdb', '--out', 'page', '--json' ], dir );
check( written.code === 0, `baker view: exit ${ written.code }, ${ written.stderr }` );
const summary = JSON.parse( written.stdout || '{}' );
check( summary.scene && summary.scene.endsWith( 'default_room.gltf' ), `the scene beside the volume is found: ${ summary.scene }` );

// The page draws on the next animation frame after a change.
const drawn = ( page ) => page.evaluate( () => new Promise( ( resolve ) => requestAnimationFrame( () => requestAnimationFrame( resolve ) ) ) );

function srgbToLinear( byte ) {
	const v = byte / 255;
	return v <= 0.04045 ? v / 12.92 : Math.pow( ( v + 0.055 ) / 1.055, 2.4 );
}

const { server, url } = await serve( null, { '/': path.join( dir, 'page' ) } );
const { browser, page, errors } = await openPage( url, { width: 1024, height: 640 } );
try {
	await page.waitForFunction( 'window.viewerReady === true || document.getElementById( "summary" ).textContent.startsWith( "cannot" )', { timeout: 90000 } ).catch( () => {} );
	check( await page.evaluate( () => window.viewerReady === true ), `the page is ready (errors: ${ errors.join( '; ' ) })` );
	const info = await page.evaluate( () => window.viewer.info );
	const [ nx, ny, nz ] = info.dims;
	const states = await page.evaluate( () => fetch( 'volume.bin' ).then( ( r ) => r.arrayBuffer() ).then( ( b ) => Array.from( new Int32Array( b ) ) ) );
	check( info.levels.length === 1 && ! info.levels[ 0 ].sections.probes, `a uniform volume is one level holding every probe: ${ JSON.stringify( info.levels.map( ( l ) => l.rows ) ) }` );
	const stateOf = ( [ i, j, k ] ) => states[ info.levels[ 0 ].sections.states.byte_offset / 4 + i + nx * ( j + ny * k ) ];
	// Three valid probes, each seen from its own side, at an exposure that shows its brightest
	// channel at 0.8 (8-bit sRGB steps stay well under 1 % there).
	const valid = [];
	for ( let k = 1; k < nz; ++ k ) for ( let j = 1; j < ny; ++ j ) for ( let i = 1; i < nx; ++ i ) if ( stateOf( [ i, j, k ] ) === 1 ) valid.push( [ i, j, k ] );
	const probes = [ valid[ 0 ], valid[ Math.floor( valid.length / 2 ) ], valid[ valid.length - 1 ] ];
	const views = [ [ 0.3, 0.4, 1 ], [ - 0.5, 0.2, 0.8 ], [ 0.6, - 0.3, 0.7 ] ];
	check( valid.length >= 3, `three valid probes to look at: ${ JSON.stringify( valid ) }` );
	for ( const [ n, ijk ] of probes.entries() ) {
		const length = Math.hypot( ...views[ n ] ), normal = views[ n ].map( ( v ) => v / length );
		const position = ijk.map( ( i, a ) => info.origin[ a ] + info.spacing * i );
		const expected = sample( path.join( dir, 'room.vdb' ), position, normal ).irradiance;
		const brightest = Math.max( ...expected );
		await page.evaluate( ( stops ) => window.viewer.setOption( 'exposure', stops ), Math.log2( 0.8 * Math.PI / brightest ) );
		const shot = await page.evaluate( ( ijk, towards ) => window.viewer.captureProbe( ijk, towards ), ijk, views[ n ] );
		const rendered = [ 0, 1, 2 ].map( ( c ) => shot.pixels.reduce( ( sum, p ) => sum + srgbToLinear( p[ c ] ), 0 ) / 4 * Math.PI / shot.exposure );
		for ( let c = 0; c < 3; ++ c ) {
			check( Math.abs( rendered[ c ] - expected[ c ] ) <= 0.02 * brightest,
				`probe ${ ijk } channel ${ c }: rendered ${ rendered[ c ].toFixed( 5 ) } (pixels ${ JSON.stringify( shot.pixels ) }), baker sample ${ expected[ c ].toFixed( 5 ) }` );
		}
		console.log( `probe ${ ijk } seen along (${ shot.normal.map( ( v ) => v.toFixed( 3 ) ) }): page E = (${ rendered.map( ( v ) => v.toFixed( 4 ) ) }), baker sample E = (${ expected.map( ( v ) => v.toFixed( 4 ) ) }); largest difference ${ ( 100 * Math.max( ...rendered.map( ( r, c ) => Math.abs( r - expected[ c ] ) ) ) / brightest ).toFixed( 2 ) } % of the brightest channel` );
	}
	await page.evaluate( () => window.viewer.setOption( 'exposure', 0 ) );

	// A relocated probe turns the state colour (yellow) when the toggle is on.
	const relocated = [];
	for ( let k = 0; k < nz; ++ k ) for ( let j = 0; j < ny; ++ j ) for ( let i = 0; i < nx; ++ i ) if ( stateOf( [ i, j, k ] ) === 2 ) relocated.push( [ i, j, k ] );
	check( relocated.length > 0, 'the room has a relocated probe' );
	if ( relocated.length ) {
		const before = await page.evaluate( ( ijk ) => window.viewer.captureProbe( ijk, [ 0, 0, 1 ] ), relocated[ 0 ] );
		await page.evaluate( () => window.viewer.setOption( 'show-states', true ) );
		const after = await page.evaluate( ( ijk ) => window.viewer.captureProbe( ijk, [ 0, 0, 1 ] ), relocated[ 0 ] );
		await page.evaluate( () => window.viewer.setOption( 'show-states', false ) );
		const [ b, a ] = [ before.pixels[ 0 ], after.pixels[ 0 ] ];
		check( a.join() !== b.join() && Math.abs( a[ 0 ] - 0xfb ) <= 2 && Math.abs( a[ 1 ] - 0xbc ) <= 2 && a[ 2 ] <= 8,
			`relocated probe ${ relocated[ 0 ] }: ${ b } with irradiance, ${ a } with states` );
	}

	// A click's six axis values are baker sample's at the same point.
	const point = [ 0.25, 1.2, 1.7 ];
	const picked = await page.evaluate( ( p ) => window.viewer.pick( p ), point );
	for ( const [ name, e ] of Object.entries( picked.irradiance ) ) {
		const axis = { X: 0, Y: 1, Z: 2 }[ name[ 1 ] ], normal = [ 0, 0, 0 ];
		normal[ axis ] = name[ 0 ] === '-' ? - 1 : 1;
		const expected = sample( path.join( dir, 'room.vdb' ), point, normal ).irradiance;
		check( e.every( ( v, c ) => Math.abs( v - expected[ c ] ) <= 1e-5 * Math.max( 1, Math.abs( expected[ c ] ) ) ), `pick ${ name }: ${ e } against ${ expected }` );
	}

	// Leak-aware: the same point with each probe weighed by its distance map, as baker sample
	// --leak-aware gives it; the walls beside the point turn probes away, so the values move.
	const canvasImage = async ( leakAware ) => {
		await page.evaluate( ( on ) => window.viewer.setOption( 'leak-aware', on ), leakAware );
		await drawn( page );
		return page.evaluate( () => document.getElementById( 'view' ).toDataURL() );
	};
	await page.evaluate( () => window.viewer.setOption( 'slice-x', true ) );
	const [ trilinearSlice, leakAwareSlice ] = [ await canvasImage( false ), await canvasImage( true ) ];
	await page.evaluate( () => window.viewer.setOption( 'slice-x', false ) );
	check( trilinearSlice !== leakAwareSlice, 'the leak-aware toggle redraws the slice' );
	const leakPicked = await page.evaluate( ( p ) => window.viewer.pick( p ), point );
	await page.evaluate( () => window.viewer.setOption( 'leak-aware', false ) );
	let moved = 0;
	for ( const [ name, e ] of Object.entries( leakPicked.irradiance ) ) {
		const axis = { X: 0, Y: 1, Z: 2 }[ name[ 1 ] ], normal = [ 0, 0, 0 ];
		normal[ axis ] = name[ 0 ] === '-' ? - 1 : 1;
		const expected = sample( path.join( dir, 'room.vdb' ), point, normal, true ).irradiance;
		check( e.every( ( v, c ) => Math.abs( v - expected[ c ] ) <= 1e-5 * Math.max( 1, Math.abs( expected[ c ] ) ) ), `leak-aware pick ${ name }: ${ e } against ${ expected }` );
		moved = Math.max( moved, ...e.map( ( v, c ) => Math.abs( v - picked.irradiance[ name ][ c ] ) / Math.max( ...expected ) ) );
	}
	check( leakPicked.leakAware && moved > 0.01, `leak-aware reading moves the point's values (largest ${ ( 100 * moved ).toFixed( 1 ) } % of the brightest channel)` );
	console.log( `leak-aware pick at ${ point }: baker sample --leak-aware's six values to 1e-5; ${ ( 100 * moved ).toFixed( 1 ) } % of the brightest channel from trilinear at most` );

	// A real click on the canvas (the default view's centre looks at the room) prints a point.
	await page.mouse.click( 700, 330 );
	const printed = await page.evaluate( () => document.getElementById( 'picked' ).textContent );
	check( /^position \(/.test( printed ) && /\+X {2}E = \(/.test( printed ) && /-Z {2}E = \(/.test( printed ), `a click prints the point and six axes: ${ printed }` );

	if ( screenshot ) {
		fs.mkdirSync( path.dirname( screenshot ), { recursive: true } );
		await page.evaluate( () => window.viewer.resetExposure() );
		await drawn( page );
		await page.screenshot( { path: screenshot } );
		console.log( `screenshot: ${ screenshot }` );
	}
	check( errors.length === 0, `console errors: ${ errors.join( '; ' ) }` );
} finally {
	await browser.close();
	server.close();
}

// --serve: the same files from baker itself, on a free port it prints.
const served = spawn( baker, [ 'view', 'room.vdb', '--out', 'page', '--serve', '0' ], { cwd: dir } );
const address = await new Promise( ( resolve ) => {
	let out = '';
	served.stdout.on( 'data', ( d ) => { out += d; const m = out.match( /http:\/\/127\.0\.0\.1:\d+\// ); if ( m ) resolve( m[ 0 ] ); } );
	setTimeout( () => resolve( null ), 30000 );
} );
check( address !== null, 'baker view --serve prints its address' );
if ( address ) {
	const index = await fetch( address );
	const json = await fetch( address + 'volume.json' ).then( ( r ) => r.json() );
	const outside = await fetch( address + '..%2f..%2froom.vdb' );
	check( index.ok && ( await index.text() ).includes( 'viewer.js' ) && json.basis === 'ad-ycocg' && outside.status === 404, `served ${ index.status }, ${ json.basis }, outside ${ outside.status }` );
}
served.kill();

await checkAdaptivePage();

// A damaged volume: the reader's message, exit 2, no page.
fs.writeFileSync( path.join( dir, 'damaged.vdb' ), fs.readFileSync( path.join( dir, 'room.vdb' ) ).subarray( 0, 400 ) );
const damaged = runBaker( [ 'view', 'damaged.vdb', '--out', 'damaged_page' ], dir );
check( damaged.code === 2 && damaged.stderr.includes( 'damaged.vdb' ) && ! fs.existsSync( path.join( dir, 'damaged_page' ) ), `damaged volume: exit ${ damaged.code }, ${ damaged.stderr.trim() }` );
const foreign = runBaker( [ 'view', 'page', '--out', 'foreign_page' ], dir );
check( foreign.code === 2 && ! fs.existsSync( path.join( dir, 'foreign_page' ) ), `a directory that is no volume: exit ${ foreign.code }, ${ foreign.stderr.trim() }` );
finish( 'viewer' );

// An adaptive volume of the window room, whose finest level holds only some of its sub-bricks: a
// level's sphere shows that level's probe as baker sample reads it at the probe; a click reads
// the level baker sample reads, coarse or fine; a level's checkbox hides its spheres.
async function checkAdaptivePage() {
	const adaptive = freshDirectory( 'viewer-adaptive' );
	for ( const file of [ 'window_room.gltf', 'window_room.bin', 'window_room_floor.png' ] ) fs.copyFileSync( path.join( sourceDir, 'data/window_room', file ), path.join( adaptive, file ) );
	bake( [ 'window_room.gltf', '--placement', 'adaptive', '--basis', 'sh-l2', '--rays', '128', '--seed', '1', '--sky', '1,1,1', '--out', 'room.vdb' ], adaptive );
	const volume = path.join( adaptive, 'room.vdb' );
	const viewed = runBaker( [ 'view', 'room.vdb', '--out', 'page', '--json' ], adaptive );
	check( viewed.code === 0 && JSON.parse( viewed.stdout || '{}' ).levels === 3, `baker view of an adaptive volume: exit ${ viewed.code }, ${ viewed.stdout } ${ viewed.stderr }` );
	if ( viewed.code !== 0 ) return;
	const { server, url } = await serve( null, { '/': path.join( adaptive, 'page' ) } );
	const { browser, page, errors } = await openPage( url, { width: 1024, height: 640 } );
	try {
		await page.waitForFunction( 'window.viewerReady === true || document.getElementById( "summary" ).textContent.startsWith( "cannot" )', { timeout: 90000 } ).catch( () => {} );
		check( await page.evaluate( () => window.viewerReady === true ), `the adaptive page is ready (errors: ${ errors.join( '; ' ) })` );
		const info = await page.evaluate( () => window.viewer.info );
		const finest = info.levels.length - 1, level = info.levels[ finest ];
		check( level.sections.sub_bricks_held && level.rows < level.dims[ 0 ] * level.dims[ 1 ] * level.dims[ 2 ], `the finest level holds some probes only: ${ level.rows } of ${ level.dims }` );
		check( await page.evaluate( () => document.getElementById( 'leak-aware' ).disabled ), 'an adaptive volume, which holds no distance maps, disables leak-aware reading' );
		const buffer = await page.evaluate( () => fetch( 'volume.bin' ).then( ( r ) => r.arrayBuffer() ).then( ( b ) => Array.from( new Uint8Array( b ) ) ) );
		const bytes = new Uint8Array( buffer ), words = new Int32Array( bytes.buffer );
		const sectionOf = ( l, name ) => { const s = info.levels[ l ].sections[ name ]; return name === 'sub_bricks_held' ? bytes.slice( s.byte_offset, s.byte_offset + s.count ) : words.slice( s.byte_offset / 4, s.byte_offset / 4 + s.count ); };
		const probesOf = ( l ) => Array.from( { length: info.levels[ l ].rows }, ( _, r ) => Array.from( sectionOf( l, 'probes' ).slice( 3 * r, 3 * r + 3 ) ) );
		const states = sectionOf( finest, 'states' ), probes = probesOf( finest );
		const valid = probes.filter( ( _, r ) => states[ r ] === 1 );
		const shown = [ valid[ Math.floor( valid.length / 3 ) ], valid[ Math.floor( 2 * valid.length / 3 ) ] ];
		for ( const ijk of shown ) {
			const position = ijk.map( ( i, a ) => level.origin[ a ] + level.spacing * i ), towards = [ 0.3, 0.5, 0.8 ];
			const normal = towards.map( ( v ) => v / Math.hypot( ...towards ) );
			const expected = sample( volume, position, normal );
			const brightest = Math.max( ...expected.irradiance );
			check( expected.level === finest && brightest > 0, `baker sample reads the finest level at its probe ${ ijk }: level ${ expected.level }, E ${ expected.irradiance }` );
			await page.evaluate( ( stops ) => window.viewer.setOption( 'exposure', stops ), Math.log2( 0.8 * Math.PI / brightest ) );
			const shot = await page.evaluate( ( ijk, towards, l ) => window.viewer.captureProbe( ijk, towards, l ), ijk, towards, finest );
			const rendered = [ 0, 1, 2 ].map( ( c ) => shot.pixels.reduce( ( sum, p ) => sum + srgbToLinear( p[ c ] ), 0 ) / 4 * Math.PI / shot.exposure );
			check( rendered.every( ( r, c ) => Math.abs( r - expected.irradiance[ c ] ) <= 0.02 * brightest ), `level ${ finest } probe ${ ijk }: rendered ${ rendered }, baker sample ${ expected.irradiance }` );
			console.log( `adaptive: level ${ finest } probe ${ ijk }: page E = (${ rendered.map( ( v ) => v.toFixed( 4 ) ) }), baker sample E = (${ expected.irradiance.map( ( v ) => v.toFixed( 4 ) ) }); largest difference ${ ( 100 * Math.max( ...rendered.map( ( r, c ) => Math.abs( r - expected.irradiance[ c ] ) ) ) / brightest ).toFixed( 2 ) } % of the brightest channel` );
			await page.evaluate( ( l ) => window.viewer.setOption( `level-${ l }`, false ), finest );
			const without = await page.evaluate( ( ijk, towards, l ) => window.viewer.captureProbe( ijk, towards, l ), ijk, towards, finest );
			await page.evaluate( ( l ) => window.viewer.setOption( `level-${ l }`, true ), finest );
			check( without.pixels[ 0 ].join() !== shot.pixels[ 0 ].join(), `unticking level ${ finest } hides its sphere at ${ ijk }: ${ without.pixels[ 0 ] }` );
		}
		// A probe of level 1 where the finest level holds one too: hidden while the finest level is
		// shown (its sphere is drawn there), drawn when it is not.
		const coarse = info.levels[ finest - 1 ], held = new Set( probes.map( ( ijk ) => ijk.join() ) );
		const coarseStates = sectionOf( finest - 1, 'states' );
		const coinciding = ( coarse.sections.probes ? probesOf( finest - 1 ) : Array.from( { length: coarse.rows }, ( _, p ) => [ p % coarse.dims[ 0 ], Math.floor( p / coarse.dims[ 0 ] ) % coarse.dims[ 1 ], Math.floor( p / ( coarse.dims[ 0 ] * coarse.dims[ 1 ] ) ) ] ) )
			.filter( ( ijk, r ) => coarseStates[ r ] === 1 && held.has( ijk.map( ( i, a ) => Math.round( ( coarse.origin[ a ] + coarse.spacing * i - level.origin[ a ] ) / level.spacing ) ).join() ) );
		check( coinciding.length > 0, 'level 1 has a probe where the finest level holds one' );
		if ( coinciding.length ) {
			const capture = () => page.evaluate( ( ijk, l ) => window.viewer.captureProbe( ijk, [ 0.3, 0.5, 0.8 ], l ), coinciding[ 0 ], finest - 1 );
			const background = ( shot ) => shot.pixels.every( ( p ) => p.join() === '32,33,36' );
			const whileFinestShown = await capture();
			await page.evaluate( ( l ) => window.viewer.setOption( `level-${ l }`, false ), finest );
			const whileFinestHidden = await capture();
			await page.evaluate( ( l ) => window.viewer.setOption( `level-${ l }`, true ), finest );
			check( background( whileFinestShown ) && ! background( whileFinestHidden ), `level ${ finest - 1 } probe ${ coinciding[ 0 ] }: ${ JSON.stringify( whileFinestShown.pixels ) } while level ${ finest } is shown, ${ JSON.stringify( whileFinestHidden.pixels ) } while it is not` );
		}

		// Points across the box, and at the middle of each sub-brick the finest level leaves out
		// (read at a coarser level); three read at each level baker sample reads them at.
		const candidates = [];
		const at = ( ijk ) => ijk.map( ( i, a ) => level.origin[ a ] + level.spacing * i );
		for ( let n = 0; n < 24; ++ n ) {
			const f = [ ( n % 4 + 0.37 ) / 4, ( Math.floor( n / 4 ) % 3 + 0.61 ) / 3, ( Math.floor( n / 12 ) + 0.29 ) / 2 ];
			candidates.push( at( f.map( ( x, a ) => x * ( level.dims[ a ] - 1 ) ) ) );
		}
		const bricks = level.dims.map( ( d ) => Math.ceil( d / 8 ) );
		sectionOf( finest, 'sub_bricks_held' ).forEach( ( mask, b ) => {
			const corner = [ b % bricks[ 0 ], Math.floor( b / bricks[ 0 ] ) % bricks[ 1 ], Math.floor( b / ( bricks[ 0 ] * bricks[ 1 ] ) ) ].map( ( x ) => 8 * x );
			for ( let sub = 0; sub < 8; ++ sub ) {
				const middle = corner.map( ( c, a ) => c + 4 * ( ( sub >> a ) & 1 ) + 1.5 );
				if ( ! ( ( mask >> sub ) & 1 ) && middle.every( ( x, a ) => x < level.dims[ a ] - 1 ) ) candidates.push( at( middle ) );
			}
		} );
		const levelOf = candidates.map( ( point ) => ( { point, level: sample( volume, point, [ 0, 1, 0 ] ).level } ) );
		const levelsRead = new Set( levelOf.map( ( c ) => c.level ) );
		console.log( `adaptive: picks at levels ${ [ ...levelsRead ].sort() } (${ [ ...levelsRead ].sort().map( ( l ) => levelOf.filter( ( c ) => c.level === l ).length ).join( ', ' ) } of the ${ levelOf.length } points)` );
		for ( const l of levelsRead ) {
			for ( const { point } of levelOf.filter( ( c ) => c.level === l ).slice( 0, 3 ) ) {
				const picked = await page.evaluate( ( p ) => window.viewer.pick( p ), point );
				for ( const [ name, e ] of Object.entries( picked.irradiance ) ) {
					const normal = [ 0, 0, 0 ];
					normal[ { X: 0, Y: 1, Z: 2 }[ name[ 1 ] ] ] = name[ 0 ] === '-' ? - 1 : 1;
					const expected = sample( volume, point, normal ).irradiance;
					check( e.every( ( v, c ) => Math.abs( v - expected[ c ] ) <= 1e-5 * Math.max( 1, Math.abs( expected[ c ] ) ) ), `adaptive pick ${ point } ${ name } (level ${ l }): ${ e } against ${ expected }` );
				}
			}
		}
		check( levelsRead.has( finest ) && levelsRead.size >= 2, `the points are read at more than one level, the finest among them: ${ [ ...levelsRead ] }` );
		check( errors.length === 0, `adaptive page console errors: ${ errors.join( '; ' ) }` );
	} finally {
		await browser.close();
		server.close();
	}
}
