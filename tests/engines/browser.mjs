// Headless Chromium for the engine and viewer tests: Debian's chromium (or BAKER_CHROMIUM),
// driven by puppeteer-core, WebGL 2 through SwiftShader, and a loopback server for the page,
// the project's decoders and npm packages, and a test's own files. Never a downloaded browser.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json' };

// routes: { '/prefix/': directory }; '/' serves `page` (HTML text) unless it is null, and a path
// ending in '/' its index.html.
export async function serve( page, routes ) {
	const server = http.createServer( ( request, response ) => {
		let url = decodeURIComponent( new URL( request.url, 'http://localhost' ).pathname );
		if ( url === '/favicon.ico' ) {
			response.writeHead( 204 );
			return response.end();
		}
		if ( url === '/' && page !== null ) {
			response.writeHead( 200, { 'content-type': 'text/html' } );
			return response.end( page );
		}
		if ( url.endsWith( '/' ) ) url += 'index.html';
		for ( const [ prefix, directory ] of Object.entries( routes ) ) {
			if ( ! url.startsWith( prefix ) ) continue;
			const file = path.join( directory, url.slice( prefix.length ) );
			if ( ! file.startsWith( directory ) || ! fs.existsSync( file ) || ! fs.statSync( file ).isFile() ) break;
			response.writeHead( 200, { 'content-type': TYPES[ path.extname( file ) ] ?? 'application/octet-stream' } );
			return fs.createReadStream( file ).pipe( response );
		}
		response.writeHead( 404 );
		response.end();
	} );
	await new Promise( ( resolve ) => server.listen( 0, '127.0.0.1', resolve ) );
	return { server, url: `http://127.0.0.1:${ server.address().port }/` };
}

export function chromiumPath() {
	const candidates = [ process.env.BAKER_CHROMIUM, '/usr/bin/chromium', '/usr/bin/chromium-browser' ].filter( Boolean );
	const found = candidates.find( ( p ) => fs.existsSync( p ) );
	if ( ! found ) throw new Error( 'no Chromium: install Debian\'s chromium (scripts/install-deps.sh does) or set BAKER_CHROMIUM' );
	return found;
}

// Opens `url`, collecting console errors and page errors into the returned list.
export async function openPage( url, viewport = { width: 512, height: 512 } ) {
	const browser = await puppeteer.launch( {
		executablePath: chromiumPath(),
		headless: true,
		args: [ '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist' ],
	} );
	const page = await browser.newPage();
	await page.setViewport( viewport );
	const errors = [];
	page.on( 'console', ( m ) => { if ( m.type() === 'error' ) errors.push( m.text() ); } );
	page.on( 'pageerror', ( e ) => errors.push( String( e ) ) );
	page.on( 'requestfailed', ( r ) => errors.push( `request failed: ${ r.url() }` ) );
	await page.goto( url, { waitUntil: 'load' } );
	return { browser, page, errors };
}

// The repository's node_modules, where `npm ci` puts them.
export function nodeModules( sourceDir ) {
	const dir = path.join( sourceDir, 'node_modules' );
	if ( ! fs.existsSync( path.join( dir, 'three' ) ) ) throw new Error( `${ dir }: no three.js; run npm ci in ${ sourceDir } (scripts/test.sh does)` );
	return dir;
}
