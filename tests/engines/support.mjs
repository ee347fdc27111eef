// What the engine-format tests share: running the real baker binary as a user would, and
// baker sample as the value every engine's reading is checked against.
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

// argv: node TEST.mjs BAKER_BINARY SOURCE_DIR
export const baker = process.argv[ 2 ] && path.resolve( process.argv[ 2 ] );
export const sourceDir = process.argv[ 3 ] && path.resolve( process.argv[ 3 ] );
if ( ! baker || ! sourceDir ) {
	console.error( 'usage: node TEST.mjs BAKER_BINARY SOURCE_DIR' );
	process.exit( 2 );
}

export function freshDirectory( name ) {
	const dir = fs.mkdtempSync( path.join( os.tmpdir(), `baker-${ name }-` ) );
	process.on( 'exit', () => fs.rmSync( dir, { recursive: true, force: true } ) );
	return dir;
}

export function runBaker( args, cwd ) {
	const r = spawnSync( baker, args, { cwd, encoding: 'utf8' } );
	if ( r.error ) throw new Error( `${ baker }: ${ r.error.message }` );
	return { code: r.status, stdout: r.stdout, stderr: r.stderr };
}

export function bake( args, cwd ) {
	const r = runBaker( [ ...args, '--quiet', '--json' ], cwd );
	if ( r.code !== 0 ) throw new Error( `baker ${ args.join( ' ' ) } exited ${ r.code }: ${ r.stderr }` );
	return JSON.parse( r.stdout );
}

// `baker sample VOLUME --at P --normal N --json [--leak-aware]`: the irradiance an engine should
// reproduce.
export function sample( volume, at, normal, leakAware = false ) {
	const out = execFileSync( baker, [ 'sample', volume, '--at', at.join( ',' ), '--normal', normal.join( ',' ), '--json', ...( leakAware ? [ '--leak-aware' ] : [] ) ], { encoding: 'utf8' } );
	return JSON.parse( out );
}

let failures = 0, checks = 0;
export function check( condition, message ) {
	++ checks;
	if ( ! condition ) {
		++ failures;
		if ( failures <= 20 ) console.error( `FAIL: ${ message }` );
	}
}

export function finish( what ) {
	console.log( `${ what }: ${ checks - failures } of ${ checks } checks passed` );
	process.exit( failures === 0 && checks > 0 ? 0 : 1 );
}
