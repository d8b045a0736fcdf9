<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="it_IT">
<context>
    <name>main</name>
    <message>
        <location filename="../app/gui/main.cpp" line="45"/>
        <source>3D object recognition for bin picking, taught from a scan</source>
        <translation>Riconoscimento 3D di oggetti per il bin picking, appreso da una scansione</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::DevicePanel</name>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="37"/>
        <source>device id, e.g. kinect:0 or file:/path/scan.pcd</source>
        <translation>id del dispositivo, es. kinect:0 o file:/percorso/scansione.pcd</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="41"/>
        <source>Refresh</source>
        <translation>Aggiorna</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="42"/>
        <location filename="../ui/panels/DevicePanel.cpp" line="100"/>
        <source>Open</source>
        <translation>Apri</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="43"/>
        <source>Capture</source>
        <translation>Acquisizione</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="44"/>
        <source>Stream</source>
        <translation>Flusso</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="83"/>
        <source>This build has no camera support (SCANPICK_BUILD_DEVICES=OFF).</source>
        <translation>Questa build non supporta le telecamere (SCANPICK_BUILD_DEVICES=OFF).</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="100"/>
        <source>Close</source>
        <translation>Chiudi</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="107"/>
        <source>Looking for cameras…</source>
        <translation>Ricerca telecamere…</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="126"/>
        <source>No camera attached. A file:&lt;path&gt; id replays saved scans.</source>
        <translation>Nessuna telecamera collegata. Un id file:&lt;percorso&gt; riproduce scansioni salvate.</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="128"/>
        <source>%1 camera(s) found</source>
        <translation>%1 telecamera/e trovata/e</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="138"/>
        <source>Choose a camera in the list or type its id.</source>
        <translation>Scegli una telecamera dall&apos;elenco o scrivine l&apos;id.</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="141"/>
        <source>Opening %1…</source>
        <translation>Apertura di %1…</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="148"/>
        <source>Open: %1</source>
        <translation>Aperta: %1</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="167"/>
        <source>Closed</source>
        <translation>Chiusa</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="181"/>
        <source>capture %1</source>
        <translation>acquisizione %1</translation>
    </message>
    <message>
        <location filename="../ui/panels/DevicePanel.cpp" line="202"/>
        <source>stream %1</source>
        <translation>flusso %1</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::LogDock</name>
    <message>
        <location filename="../ui/panels/LogDock.cpp" line="46"/>
        <source>Log</source>
        <translation>Registro</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::MainWindow</name>
    <message>
        <source>the scan&apos;s file name</source>
        <translation>il nome del file della scansione</translation>
    </message>
    <message>
        <source>Give every view of one part the same name: only views of one part are searched together</source>
        <translation>Date lo stesso nome a ogni vista di un pezzo: si cercano insieme solo viste di un pezzo</translation>
    </message>
    <message>
        <source>Part name:</source>
        <translation>Nome del pezzo:</translation>
    </message>
    <message>
        <source>x, y, z (mm), qw, qx, qy, qz (optional)</source>
        <translation>x, y, z (mm), qw, qx, qy, qz (facoltativa)</translation>
    </message>
    <message>
        <source>Where the part lies in this scan (from a fixture, or the robot that placed it): views that know it are joined, each knowing the others</source>
        <translation>Dove si trova il pezzo in questa scansione (da un&apos;attrezzatura, o dal robot che l&apos;ha posato): le viste che lo sanno vengono unite, ciascuna conoscendo le altre</translation>
    </message>
    <message>
        <source>Part pose:</source>
        <translation>Posa del pezzo:</translation>
    </message>
    <message>
        <source>&amp;Add model view…</source>
        <translation>&amp;Aggiungi vista del modello…</translation>
    </message>
    <message>
        <source>Add model view</source>
        <translation>Aggiungi vista del modello</translation>
    </message>
    <message>
        <source>Add views of the same part, taught from scans of its other sides: Recognize searches them all</source>
        <translation>Aggiungi viste dello stesso pezzo, insegnate da scansioni dei suoi altri lati: Riconosci le cerca tutte</translation>
    </message>
    <message>
        <source>Model %1: %2 views, %3 of them joined</source>
        <translation>Modello %1: %2 viste, %3 unite</translation>
    </message>
    <message>
        <source>taught</source>
        <translation>insegnato</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="41"/>
        <source>scanpick</source>
        <translation>scanpick</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="64"/>
        <source>Cancel</source>
        <translation>Annulla</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="86"/>
        <source>Cancelled</source>
        <translation>Annullato</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="93"/>
        <source>Open a scan (Ctrl+O) or drop a PCD/PLY file here</source>
        <translation>Apri una scansione (Ctrl+O) o trascina qui un file PCD/PLY</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="109"/>
        <source>Parameters</source>
        <translation>Parametri</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="119"/>
        <source>Results</source>
        <translation>Risultati</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="126"/>
        <source>Capture</source>
        <translation>Acquisizione</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="136"/>
        <source>Camera</source>
        <translation>Telecamera</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="145"/>
        <source>&amp;File</source>
        <translation>&amp;File</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="146"/>
        <source>&amp;Open scan or model…</source>
        <translation>&amp;Apri scansione o modello…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="149"/>
        <source>Open</source>
        <translation>Apri</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="150"/>
        <source>Scans and models (*.pcd *.ply *.spmodel);;All files (*)</source>
        <translation>Scansioni e modelli (*.pcd *.ply *.spmodel);;Tutti i file (*)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="155"/>
        <source>Open &amp;recent</source>
        <translation>Apri &amp;recenti</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="158"/>
        <source>&amp;Save model…</source>
        <translation>&amp;Salva modello…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="160"/>
        <location filename="../ui/MainWindow.cpp" line="161"/>
        <location filename="../ui/MainWindow.cpp" line="407"/>
        <location filename="../ui/MainWindow.cpp" line="417"/>
        <source>Save model</source>
        <translation>Salva modello</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="160"/>
        <location filename="../ui/MainWindow.cpp" line="407"/>
        <source>Teach or open a model first.</source>
        <translation>Prima insegna o apri un modello.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="162"/>
        <source>Models (*.spmodel)</source>
        <translation>Modelli (*.spmodel)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="167"/>
        <source>Save &amp;scan…</source>
        <translation>Salva s&amp;cansione…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="169"/>
        <location filename="../ui/MainWindow.cpp" line="170"/>
        <location filename="../ui/MainWindow.cpp" line="391"/>
        <location filename="../ui/MainWindow.cpp" line="400"/>
        <source>Save scan</source>
        <translation>Salva scansione</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="169"/>
        <location filename="../ui/MainWindow.cpp" line="391"/>
        <source>Open or capture a scan first.</source>
        <translation>Prima apri o acquisisci una scansione.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="171"/>
        <source>Scans (*.pcd *.ply)</source>
        <translation>Scansioni (*.pcd *.ply)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="206"/>
        <source>&amp;Lasso crop</source>
        <translation>Ritaglio a &amp;lazo</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="209"/>
        <source>Draw around the part with the left button: the points inside are kept (undo with Ctrl+Z)</source>
        <translation>Disegna attorno al pezzo con il tasto sinistro: i punti all&apos;interno vengono mantenuti (annulla con Ctrl+Z)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="212"/>
        <source>&amp;Preview floor</source>
        <translation>&amp;Anteprima pavimento</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="215"/>
        <source>Show the floor points (orange) that Remove floor would take away</source>
        <translation>Mostra i punti del pavimento (arancione) che Rimuovi pavimento eliminerebbe</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="397"/>
        <location filename="../ui/MainWindow.cpp" line="414"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="144"/>
        <source>Saved %1</source>
        <translation>Salvato %1</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="175"/>
        <source>&amp;Export results…</source>
        <translation>&amp;Esporta risultati…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="176"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="137"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="147"/>
        <source>Export results</source>
        <translation>Esporta risultati</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="177"/>
        <source>Results (*.json)</source>
        <translation>Risultati (*.json)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="181"/>
        <source>Save screens&amp;hot…</source>
        <translation>Salva sc&amp;hermata…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="182"/>
        <source>Save screenshot</source>
        <translation>Salva schermata</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="183"/>
        <source>Images (*.png)</source>
        <translation>Immagini (*.png)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="189"/>
        <source>&amp;Quit</source>
        <translation>&amp;Esci</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="191"/>
        <source>&amp;Edit</source>
        <translation>&amp;Modifica</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="192"/>
        <source>&amp;Undo</source>
        <translation>&amp;Annulla</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="194"/>
        <source>&amp;Redo</source>
        <translation>&amp;Ripeti</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="199"/>
        <source>&amp;Teach</source>
        <translation>&amp;Insegna</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="200"/>
        <source>Crop &amp;box</source>
        <translation>&amp;Box di ritaglio</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="204"/>
        <source>&amp;Apply crop</source>
        <translation>&amp;Applica ritaglio</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="217"/>
        <source>Remove &amp;floor</source>
        <translation>Rimuovi &amp;pavimento</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="219"/>
        <source>Place &amp;grip points</source>
        <translation>Posiziona punti di &amp;presa</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="222"/>
        <location filename="../ui/MainWindow.cpp" line="260"/>
        <source>&amp;Teach model</source>
        <translation>&amp;Insegna modello</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="225"/>
        <location filename="../ui/MainWindow.cpp" line="226"/>
        <source>&amp;Recognize</source>
        <translation>&amp;Riconosci</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="227"/>
        <source>&amp;Cancel</source>
        <translation>&amp;Annulla</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="228"/>
        <source>&amp;Live</source>
        <translation>&amp;Continuo</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="233"/>
        <source>&amp;View</source>
        <translation>&amp;Vista</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="234"/>
        <source>&amp;Reset camera</source>
        <translation>&amp;Ripristina vista</translation>
    </message>
    <message>
        <source>&amp;Language</source>
        <translation>&amp;Lingua</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="250"/>
        <source>Main</source>
        <translation>Principale</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="329"/>
        <source>Loading %1…</source>
        <translation>Caricamento di %1…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="340"/>
        <source>Open scan</source>
        <translation>Apri scansione</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="341"/>
        <source>Could not open %1</source>
        <translation>Impossibile aprire %1</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="357"/>
        <source>scanpick — %1</source>
        <translation>scanpick — %1</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="359"/>
        <source>%1: %2 points</source>
        <translation>%1: %2 punti</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="381"/>
        <source>Model %1 loaded</source>
        <translation>Modello %1 caricato</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="384"/>
        <source>Open model</source>
        <translation>Apri modello</translation>
    </message>
    <message>
        <source>Language</source>
        <translation type="vanished">Lingua</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="474"/>
        <source>Screenshot</source>
        <translation>Schermata</translation>
    </message>
    <message>
        <location filename="../ui/MainWindow.cpp" line="474"/>
        <source>Could not write %1: check the folder exists and is writable.</source>
        <translation>Impossibile scrivere %1: verifica che la cartella esista e sia scrivibile.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="53"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="55"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="78"/>
        <source>Recognize</source>
        <translation>Riconosci</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="53"/>
        <source>Teach a model or open one (.spmodel) first.</source>
        <translation>Prima insegna un modello o aprine uno (.spmodel).</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="55"/>
        <source>Open or capture a scene first.</source>
        <translation>Prima apri o acquisisci una scena.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="61"/>
        <source>Recognizing…</source>
        <translation>Riconoscimento…</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/MainWindowRecognize.cpp" line="70"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="207"/>
        <source>%n detection(s)</source>
        <translation>
            <numerusform>%n rilevamento</numerusform>
            <numerusform>%n rilevamenti</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/MainWindowRecognize.cpp" line="75"/>
        <source>Found %n instance(s)</source>
        <translation>
            <numerusform>Trovata %n istanza</numerusform>
            <numerusform>Trovate %n istanze</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="95"/>
        <source>Recognition cancelled</source>
        <translation>Riconoscimento annullato</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="131"/>
        <source>Detection %1: score %2</source>
        <translation>Rilevamento %1: punteggio %2</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="137"/>
        <source>Run a recognition first (F5).</source>
        <translation>Prima esegui un riconoscimento (F5).</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="164"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="173"/>
        <location filename="../ui/MainWindowRecognize.cpp" line="218"/>
        <source>Live</source>
        <translation>Continuo</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="164"/>
        <source>Live needs a model and an open camera (Capture panel).</source>
        <translation>La modalità continua richiede un modello e una telecamera aperta (pannello Acquisizione).</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="173"/>
        <source>This build has no camera support.</source>
        <translation>Questa build non supporta le telecamere.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowRecognize.cpp" line="209"/>
        <source>cycle %1 ms</source>
        <translation>ciclo %1 ms</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/MainWindowRecognize.cpp" line="210"/>
        <source>Live: %n instance(s), cycle %1 ms</source>
        <translation>
            <numerusform>Continuo: %n istanza, ciclo %1 ms</numerusform>
            <numerusform>Continuo: %n istanze, ciclo %1 ms</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="86"/>
        <source>Grip points (double-click to rename):</source>
        <translation>Punti di presa (doppio clic per rinominare):</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="90"/>
        <source>Remove grip point</source>
        <translation>Rimuovi punto di presa</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="105"/>
        <location filename="../ui/MainWindowTeach.cpp" line="357"/>
        <location filename="../ui/MainWindowTeach.cpp" line="390"/>
        <source>Teach</source>
        <translation>Insegna</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="210"/>
        <source>Show the crop box first (Ctrl+B)</source>
        <translation>Prima mostra il box di ritaglio (Ctrl+B)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="216"/>
        <location filename="../ui/MainWindowTeach.cpp" line="220"/>
        <source>Crop</source>
        <translation>Ritaglio</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="216"/>
        <source>The crop box holds no point: move or enlarge it.</source>
        <translation>Il box di ritaglio non contiene punti: spostalo o ingrandiscilo.</translation>
    </message>
    <message>
        <source>Removing the floor…</source>
        <translation type="vanished">Rimozione del pavimento…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="45"/>
        <source>Sensor:</source>
        <translation>Sensore:</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="48"/>
        <source>Sensor of scans that do not tell (unorganized clouds). An organized scan whose grid matches a sensor uses that sensor.</source>
        <translation>Sensore delle scansioni che non lo indicano (nuvole non organizzate). Una scansione organizzata la cui griglia corrisponde a un sensore usa quel sensore.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="68"/>
        <source>Apply crop box</source>
        <translation>Applica box di ritaglio</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="92"/>
        <source>Open a scan first</source>
        <translation>Prima apri una scansione</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="102"/>
        <source>Lasso: drag around the part; the points inside are kept</source>
        <translation>Lazo: trascina attorno al pezzo; i punti all&apos;interno vengono mantenuti</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="112"/>
        <source>Lasso too small: drag around the part</source>
        <translation>Lazo troppo piccolo: trascina attorno al pezzo</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="119"/>
        <source>Lasso crop…</source>
        <translation>Ritaglio a lazo…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="128"/>
        <location filename="../ui/MainWindowTools.cpp" line="132"/>
        <location filename="../ui/MainWindowTools.cpp" line="135"/>
        <source>Lasso crop</source>
        <translation>Ritaglio a lazo</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="128"/>
        <source>The lasso holds no point: draw around the part.</source>
        <translation>Il lazo non contiene punti: disegna attorno al pezzo.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="133"/>
        <source>Lasso kept %1 points (Ctrl+Z undoes)</source>
        <translation>Il lazo ha mantenuto %1 punti (Ctrl+Z annulla)</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="154"/>
        <location filename="../ui/MainWindowTools.cpp" line="199"/>
        <source>Floor</source>
        <translation>Pavimento</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="154"/>
        <source>Open a scan first.</source>
        <translation>Prima apri una scansione.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="157"/>
        <source>Looking for the floor…</source>
        <translation>Ricerca del pavimento…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="192"/>
        <source>No plane large enough to remove</source>
        <translation>Nessun piano abbastanza grande da rimuovere</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="193"/>
        <source>%1 floor points shown in orange: Remove floor takes them away</source>
        <translation>%1 punti del pavimento in arancione: Rimuovi pavimento li elimina</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="215"/>
        <source>Remove floor</source>
        <translation>Rimuovi pavimento</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTools.cpp" line="217"/>
        <source>Removed %1 floor points (Ctrl+Z undoes)</source>
        <translation>Rimossi %1 punti del pavimento (Ctrl+Z annulla)</translation>
    </message>
    <message>
        <source>Removed %1 floor points</source>
        <translation type="vanished">Rimossi %1 punti del pavimento</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="248"/>
        <source>grip %1</source>
        <translation>presa %1</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="326"/>
        <source>Preview: %1</source>
        <translation>Anteprima: %1</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="343"/>
        <source>keypoints %1 · lines %2 · circles %3</source>
        <translation>keypoint %1 · linee %2 · cerchi %3</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="349"/>
        <source>keypoints %1 ms · features %2 ms</source>
        <translation>keypoint %1 ms · feature %2 ms</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="352"/>
        <source>keypoints cached · features %1 ms</source>
        <translation>keypoint in cache · feature %1 ms</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="357"/>
        <source>Open a scan and crop the part first.</source>
        <translation>Prima apri una scansione e ritaglia il pezzo.</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="371"/>
        <source>Teaching…</source>
        <translation>Apprendimento…</translation>
    </message>
    <message>
        <location filename="../ui/MainWindowTeach.cpp" line="387"/>
        <source>Model taught: %1 features. Save it with Ctrl+S.</source>
        <translation>Modello appreso: %1 feature. Salvalo con Ctrl+S.</translation>
    </message>
    <message>
        <source>&amp;Help</source>
        <translation>&amp;Aiuto</translation>
    </message>
    <message>
        <source>&amp;User guide</source>
        <translation>&amp;Guida utente</translation>
    </message>
    <message>
        <source>&amp;About scanpick</source>
        <translation>&amp;Informazioni su scanpick</translation>
    </message>
    <message>
        <source>About scanpick</source>
        <translation>Informazioni su scanpick</translation>
    </message>
    <message>
        <source>User guide</source>
        <translation>Guida utente</translation>
    </message>
    <message>
        <source>Could not open the user guide (%1): open it with any text viewer.</source>
        <translation>Impossibile aprire la guida utente (%1): aprila con un qualsiasi visualizzatore di testo.</translation>
    </message>
    <message>
        <source>&lt;h3&gt;scanpick %1&lt;/h3&gt;&lt;p&gt;3D object recognition for bin picking, taught from a scan.&lt;/p&gt;&lt;p&gt;Built with Qt %2 and VTK %3.&lt;/p&gt;&lt;p&gt;User guide: %4&lt;/p&gt;</source>
        <translation>&lt;h3&gt;scanpick %1&lt;/h3&gt;&lt;p&gt;Riconoscimento 3D di oggetti per il bin picking, appreso da una scansione.&lt;/p&gt;&lt;p&gt;Compilato con Qt %2 e VTK %3.&lt;/p&gt;&lt;p&gt;Guida utente: %4&lt;/p&gt;</translation>
    </message>
    <message>
        <source>Show &amp;keypoints</source>
        <translation>Mostra punti &amp;chiave</translation>
    </message>
    <message>
        <source>Show f&amp;eatures</source>
        <translation>Mostra f&amp;eature</translation>
    </message>
    <message>
        <source>Move grip point</source>
        <translation>Sposta punto di presa</translation>
    </message>
    <message>
        <source>Approach:</source>
        <translation>Approccio:</translation>
    </message>
    <message>
        <source>Direction the gripper moves in to reach the selected grip point (scan frame: x, y, z, any length; Enter applies); placing or moving a point sets it against the surface normal</source>
        <translation>Direzione in cui la pinza si muove per raggiungere il punto di presa selezionato (sistema della scansione: x, y, z, lunghezza qualsiasi; Invio applica); posare o spostare un punto la imposta contro la normale della superficie</translation>
    </message>
    <message>
        <source>The approach is three numbers x, y, z, not all zero (e.g. 0, 0, 1)</source>
        <translation>L'approccio è formato da tre numeri x, y, z, non tutti nulli (per es. 0, 0, 1)</translation>
    </message>
    <message>
        <source>Set grip approach</source>
        <translation>Imposta approccio di presa</translation>
    </message>
    <message>
        <source>Add grip point</source>
        <translation>Aggiungi punto di presa</translation>
    </message>
    <message>
        <source>Rename grip point</source>
        <translation>Rinomina punto di presa</translation>
    </message>
    <message>
        <source>Select a grip point in the list, then click on the part where it should be</source>
        <translation>Seleziona un punto di presa nella lista, poi fai clic sul pezzo dove deve stare</translation>
    </message>
    <message>
        <source>Select the grip point to move in the list first</source>
        <translation>Seleziona prima nella lista il punto di presa da spostare</translation>
    </message>
    <message>
        <source>Click on the part where the grip point should be</source>
        <translation>Fai clic sul pezzo dove deve stare il punto di presa</translation>
    </message>
    <message>
        <source>Del removes the selected grip point; Ctrl+Z undoes</source>
        <translation>Canc rimuove il punto di presa selezionato; Ctrl+Z annulla</translation>
    </message>
    <message>
        <source>preprocess %1 · clustering %2 · keypoints %3 · features %4 · matching %5 · refine %6 · total %7 ms</source>
        <translation>pre-elaborazione %1 · clustering %2 · punti chiave %3 · feature %4 · abbinamento %5 · rifinitura %6 · totale %7 ms</translation>
    </message>
    <message>
        <source>Deriving the parameters from the part and teaching…</source>
        <translation>Derivazione dei parametri dal pezzo e apprendimento…</translation>
    </message>
    <message>
        <source>point spacing %1 mm, depth noise %2 mm, part diameter %3 mm</source>
        <translation>passo tra i punti %1 mm, rumore di profondità %2 mm, diametro del pezzo %3 mm</translation>
    </message>
    <message>
        <source>Parameters derived from the part: %1 (the values marked “derived” in the Parameters panel).</source>
        <translation>Parametri derivati dal pezzo: %1 (i valori segnati “derivato” nel pannello Parametri).</translation>
    </message>
    <message>
        <source>Model taught: %1 features, with parameters derived from the part. Save it with Ctrl+S.</source>
        <translation>Modello appreso: %1 feature, con parametri derivati dal pezzo. Salvalo con Ctrl+S.</translation>
    </message>
    <message>
        <source>Depth image</source>
        <translation>Immagine di profondità</translation>
    </message>
    <message>
        <source>View coverage</source>
        <translation>Copertura delle viste</translation>
    </message>
    <message>
        <source>&amp;Undo %1</source>
        <translation>&amp;Annulla %1</translation>
    </message>
    <message>
        <source>&amp;Redo %1</source>
        <translation>&amp;Ripeti %1</translation>
    </message>
    <message>
        <source>T&amp;ools</source>
        <translation>&amp;Strumenti</translation>
    </message>
    <message>
        <source>&amp;Hand-eye calibration…</source>
        <translation>Calibrazione &amp;mano-occhio…</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::ParameterPanel</name>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="50"/>
        <source>Bundled parameter presets</source>
        <translation>Preset di parametri inclusi</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="51"/>
        <source>Load…</source>
        <translation>Carica…</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="52"/>
        <source>Save…</source>
        <translation>Salva…</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="65"/>
        <location filename="../ui/panels/ParameterPanel.cpp" line="76"/>
        <location filename="../ui/panels/ParameterPanel.cpp" line="87"/>
        <source>Preset</source>
        <translation>Preset</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="69"/>
        <source>Load preset</source>
        <translation>Carica preset</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="70"/>
        <location filename="../ui/panels/ParameterPanel.cpp" line="81"/>
        <source>Presets (*.json)</source>
        <translation>Preset (*.json)</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="81"/>
        <source>Save preset</source>
        <translation>Salva preset</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="111"/>
        <source>Random</source>
        <translation>Casualità</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="116"/>
        <source>Seed of every random choice: the same scan, parameters and seed give the same result.</source>
        <translation>Seme di ogni scelta casuale: stessa scansione, parametri e seme danno lo stesso risultato.</translation>
    </message>
    <message>
        <location filename="../ui/panels/ParameterPanel.cpp" line="118"/>
        <source>Seed</source>
        <translation>Seme</translation>
    </message>
    <message>
        <source>Derived from the part (default)</source>
        <translation>Derivati dal pezzo (predefinito)</translation>
    </message>
    <message>
        <source>Teach derives every parameter from the part and the scan (point spacing, depth noise, the part&apos;s size) and shows each here with its reason. Values you change by hand before teaching override the derived ones, as --set does on the command line. A preset below is used as it is, with nothing derived.</source>
        <translation>L&apos;apprendimento deriva ogni parametro dal pezzo e dalla scansione (passo tra i punti, rumore di profondità, dimensione del pezzo) e li mostra qui, ciascuno con il suo motivo. I valori cambiati a mano prima dell&apos;apprendimento sostituiscono quelli derivati, come --set sulla riga di comando. Un preset qui sotto si usa così com&apos;è, senza derivare nulla.</translation>
    </message>
    <message>
        <source>Values marked “derived” come from the part and the scan at teach: hover one for its reason. Values you change override them at the next teach.</source>
        <translation>I valori segnati “derivato” vengono dal pezzo e dalla scansione all&apos;apprendimento: passa sopra uno per il suo motivo. I valori che cambi li sostituiscono al prossimo apprendimento.</translation>
    </message>
    <message>
        <source>derived</source>
        <translation>derivato</translation>
    </message>
    <message>
        <source>Show advanced parameters</source>
        <translation>Mostra i parametri avanzati</translation>
    </message>
    <message>
        <source>Shown first are the parameters tuned for a cell: the floor, the split into objects, verification, how many detections and ICP. Teach derives the others from the part and the scan.</source>
        <translation>Per primi si vedono i parametri che si regolano per una cella: il pavimento, la divisione in oggetti, la verifica, quante rilevazioni e l&apos;ICP. Gli altri li deriva l&apos;apprendimento dal pezzo e dalla scansione.</translation>
    </message>
    <message>
        <source>Derived from the part: %1</source>
        <translation>Derivato dal pezzo: %1</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::ResultsTable</name>
    <message>
        <source>View</source>
        <translation>Vista</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="11"/>
        <source>Score</source>
        <translation>Punteggio</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="11"/>
        <source>Position x, y, z (mm)</source>
        <translation>Posizione x, y, z (mm)</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="12"/>
        <source>Orientation r, p, y (°)</source>
        <translation>Orientamento r, p, y (°)</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="12"/>
        <source>Cluster</source>
        <translation>Cluster</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="12"/>
        <source>Grip points (mm)</source>
        <translation>Punti di presa (mm)</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="42"/>
        <source>(turn free)</source>
        <translation>(rotazione libera)</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="43"/>
        <source>The view that found this part is round about its axis (direction %1, %2, %3), or round but for a detail this scan does not show (a cup&apos;s handle): its turn about that axis is not seen. Grip points on the axis are right.</source>
        <translation>La vista che ha trovato questo pezzo è rotonda attorno al suo asse (direzione %1, %2, %3), o rotonda tranne un dettaglio che questa scansione non mostra (il manico di una tazza): la sua rotazione attorno a quell&apos;asse non si vede. I punti di presa sull&apos;asse sono corretti.</translation>
    </message>
    <message>
        <location filename="../ui/panels/ResultsTable.cpp" line="52"/>
        <source>(turn unsure)</source>
        <translation>(rotazione incerta)</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels/ResultsTable.cpp" line="54"/>
        <source>This scan cannot tell this pose from %n other pose(s) of the part: the view is nearly symmetric and the detail that tells them apart is hidden. Grip points that move between them must not be trusted.</source>
        <translation>
            <numerusform>Questa scansione non distingue questa posa da %n altra posa del pezzo: la vista è quasi simmetrica e il dettaglio che le distingue è nascosto. Non fidarsi dei punti di presa che cambiano tra le due.</numerusform>
            <numerusform>Questa scansione non distingue questa posa da altre %n pose del pezzo: la vista è quasi simmetrica e il dettaglio che le distingue è nascosto. Non fidarsi dei punti di presa che cambiano tra le pose.</numerusform>
        </translation>
    </message>
    <message>
        <source>Detection %1: drawn in this colour, labelled %1 in the view</source>
        <translation>Rilevamento %1: disegnato in questo colore, etichettato %1 nella vista</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::DepthView</name>
    <message>
        <source>Open or capture a scan to see its depth image.</source>
        <translation>Apri o acquisisci una scansione per vederne l’immagine di profondità.</translation>
    </message>
    <message>
        <source>No depth image: this scan is a list of points without the sensor&apos;s grid (an unorganized cloud). Scans saved by a PhoXi or a Kinect keep the grid; clouds that were filtered, merged or converted from a mesh lose it.</source>
        <translation>Nessuna immagine di profondità: questa scansione è un elenco di punti senza la griglia del sensore (una nuvola non organizzata). Le scansioni salvate da un PhoXi o da un Kinect conservano la griglia; le nuvole filtrate, unite o convertite da una mesh la perdono.</translation>
    </message>
    <message>
        <source>Drawing the depth image…</source>
        <translation>Disegno dell’immagine di profondità…</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::CoveragePanel</name>
    <message>
        <source>from straight above (+Z)</source>
        <translation>direttamente da sopra (+Z)</translation>
    </message>
    <message>
        <source>from straight below (−Z)</source>
        <translation>direttamente da sotto (−Z)</translation>
    </message>
    <message>
        <source>from above (elevation %1°, azimuth %2°)</source>
        <translation>da sopra (elevazione %1°, azimut %2°)</translation>
    </message>
    <message>
        <source>from below (elevation %1°, azimuth %2°)</source>
        <translation>da sotto (elevazione %1°, azimut %2°)</translation>
    </message>
    <message>
        <source>from the side at azimuth %1° (elevation %2°)</source>
        <translation>di lato con azimut %1° (elevazione %2°)</translation>
    </message>
    <message>
        <source>No model: open one (File → Open scan or model…) or teach one to see which viewing directions its views cover.</source>
        <translation>Nessun modello: aprine uno (File → Apri scansione o modello…) o insegnane uno per vedere quali direzioni di osservazione coprono le sue viste.</translation>
    </message>
    <message>
        <source>Measuring the view coverage…</source>
        <translation>Misura della copertura delle viste…</translation>
    </message>
    <message>
        <source>The view coverage could not be measured: %1</source>
        <translation>Impossibile misurare la copertura delle viste: %1</translation>
    </message>
    <message>
        <source>A direction is covered when it lies within %1° of a taught view&apos;s own viewing direction. Views left out do not know their place in the part (teach them with the part&apos;s pose) and are not counted.</source>
        <translation>Una direzione è coperta quando dista al più %1° dalla direzione di osservazione di una vista insegnata. Le viste escluse non conoscono la loro posizione nel pezzo (insegnale con la posa del pezzo) e non sono contate.</translation>
    </message>
    <message>
        <source>covered</source>
        <translation>coperta</translation>
    </message>
    <message>
        <source>not covered</source>
        <translation>non coperta</translation>
    </message>
    <message>
        <source>taught view</source>
        <translation>vista insegnata</translation>
    </message>
    <message>
        <source>suggested view</source>
        <translation>vista suggerita</translation>
    </message>
    <message>
        <source>Every viewing direction is covered.</source>
        <translation>Ogni direzione di osservazione è coperta.</translation>
    </message>
    <message>
        <source>To cover more, teach the part seen:</source>
        <translation>Per coprire di più, insegna il pezzo visto:</translation>
    </message>
    <message>
        <source>%1. %2: direction (%3, %4, %5) in the part frame</source>
        <translation>%1. %2: direzione (%3, %4, %5) nel sistema di riferimento del pezzo</translation>
    </message>
    <message>
        <source>What a scan of each view may leave open:</source>
        <translation>Che cosa una scansione di ogni vista può lasciare aperto:</translation>
    </message>
    <message>
        <source>View %1: %2</source>
        <translation>Vista %1: %2</translation>
    </message>
    <message>
        <source>Rotations a view&apos;s own surface cannot pin (an axis of revolution, a near symmetry). A detection reports them as its free turn axis or its alternative poses wherever the scan does not tell them apart.</source>
        <translation>Rotazioni che la superficie della vista da sola non può fissare (un asse di rivoluzione, una quasi simmetria). Un rilevamento le riporta come asse di rotazione libera o come pose alternative dove la scansione non le distingue.</translation>
    </message>
    <message>
        <source>Directions from the part towards the camera, in the part frame: azimuth in the XY plane from +X towards +Y, elevation from the XY plane towards +Z.</source>
        <translation>Direzioni dal pezzo verso la telecamera, nel sistema di riferimento del pezzo: azimut nel piano XY da +X verso +Y, elevazione dal piano XY verso +Z.</translation>
    </message>
    <message numerus="yes">
        <source>%n view(s) placed (%1 left out): %2 % of the viewing directions covered</source>
        <translation>
            <numerusform>%n vista collocata (escluse: %1): %2 % delle direzioni di osservazione coperte</numerusform>
            <numerusform>%n viste collocate (escluse: %1): %2 % delle direzioni di osservazione coperte</numerusform>
        </translation>
    </message>
</context>
<context>
    <name>scanpick::ui::CoverageSphere</name>
    <message>
        <source>From above (+Z)</source>
        <translation>Da sopra (+Z)</translation>
    </message>
    <message>
        <source>From below (−Z)</source>
        <translation>Da sotto (−Z)</translation>
    </message>
</context>
<context>
    <name>scanpick::ui::CalibrationWizard</name>
    <message>
        <source>Hand-eye calibration</source>
        <translation>Calibrazione mano-occhio</translation>
    </message>
    <message>
        <source>Mode:</source>
        <translation>Modalità:</translation>
    </message>
    <message>
        <source>Scan units:</source>
        <translation>Unità delle scansioni:</translation>
    </message>
    <message>
        <source>Robot positions:</source>
        <translation>Posizioni del robot:</translation>
    </message>
    <message>
        <source>Target file:</source>
        <translation>File del bersaglio:</translation>
    </message>
    <message>
        <source>Poses file:</source>
        <translation>File delle pose:</translation>
    </message>
    <message>
        <source>Eye-to-hand: fixed camera, target on the flange</source>
        <translation>Eye-to-hand: telecamera fissa, bersaglio sulla flangia</translation>
    </message>
    <message>
        <source>Eye-in-hand: camera on the flange, fixed target</source>
        <translation>Eye-in-hand: telecamera sulla flangia, bersaglio fisso</translation>
    </message>
    <message>
        <source>millimetres (mm)</source>
        <translation>millimetri (mm)</translation>
    </message>
    <message>
        <source>metres (m)</source>
        <translation>metri (m)</translation>
    </message>
    <message>
        <source>as the scans</source>
        <translation>come le scansioni</translation>
    </message>
    <message>
        <source>Eye-to-hand finds the camera in the robot base (T_base_camera) and the target on the flange (T_flange_target); eye-in-hand finds the camera on the flange (T_flange_camera) and the target in the base (T_base_target).</source>
        <translation>Eye-to-hand trova la telecamera nella base del robot (T_base_camera) e il bersaglio sulla flangia (T_flange_target); eye-in-hand trova la telecamera sulla flangia (T_flange_camera) e il bersaglio nella base (T_base_target).</translation>
    </message>
    <message>
        <source>Units of the robot&apos;s flange positions in the poses file (a UR robot reports m)</source>
        <translation>Unità delle posizioni della flangia del robot nel file delle pose (un robot UR le dà in m)</translation>
    </message>
    <message>
        <source>built-in target: 4 spheres on a 200 × 160 mm plate</source>
        <translation>bersaglio predefinito: 4 sfere su una piastra di 200 × 160 mm</translation>
    </message>
    <message>
        <source>no poses file loaded</source>
        <translation>nessun file delle pose caricato</translation>
    </message>
    <message>
        <source>Browse…</source>
        <translation>Sfoglia…</translation>
    </message>
    <message>
        <source>Load poses…</source>
        <translation>Carica pose…</translation>
    </message>
    <message>
        <source>&amp;Calibrate</source>
        <translation>&amp;Calibra</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Annulla</translation>
    </message>
    <message>
        <source>&amp;Save calibration…</source>
        <translation>&amp;Salva calibrazione…</translation>
    </message>
    <message>
        <source>Close</source>
        <translation>Chiudi</translation>
    </message>
    <message>
        <source>Scan</source>
        <translation>Scansione</translation>
    </message>
    <message>
        <source>Flange position (mm)</source>
        <translation>Posizione della flangia (mm)</translation>
    </message>
    <message>
        <source>Spheres</source>
        <translation>Sfere</translation>
    </message>
    <message>
        <source>Fit RMS (mm)</source>
        <translation>RMS adattamento (mm)</translation>
    </message>
    <message>
        <source>RMS (mm)</source>
        <translation>RMS (mm)</translation>
    </message>
    <message>
        <source>Max (mm)</source>
        <translation>Max (mm)</translation>
    </message>
    <message>
        <source>Rotation (°)</source>
        <translation>Rotazione (°)</translation>
    </message>
    <message>
        <source>Status</source>
        <translation>Stato</translation>
    </message>
    <message>
        <source>The poses file could not be read: %1</source>
        <translation>Impossibile leggere il file delle pose: %1</translation>
    </message>
    <message>
        <source>Calibration failed, nothing was written: %1</source>
        <translation>Calibrazione non riuscita, non è stato scritto nulla: %1</translation>
    </message>
    <message>
        <source>Calibration cancelled.</source>
        <translation>Calibrazione annullata.</translation>
    </message>
    <message>
        <source>Calibration saved to %1.</source>
        <translation>Calibrazione salvata in %1.</translation>
    </message>
    <message>
        <source>The calibration was not saved: %1</source>
        <translation>La calibrazione non è stata salvata: %1</translation>
    </message>
    <message>
        <source>calibrate first</source>
        <translation>calibrare prima</translation>
    </message>
    <message>
        <source>Load a poses file: the scans of the calibration target and the robot&apos;s flange pose at each (docs/calibration.md).</source>
        <translation>Caricare un file delle pose: le scansioni del bersaglio di calibrazione e la posa della flangia del robot per ciascuna (docs/calibration.md).</translation>
    </message>
    <message numerus="yes">
        <source>%n pose(s) loaded: press Calibrate.</source>
        <translation>
            <numerusform>%n posa caricata: premere Calibra.</numerusform>
            <numerusform>%n pose caricate: premere Calibra.</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <source>Calibrating: finding the target in %n scan(s)…</source>
        <translation>
            <numerusform>Calibrazione: ricerca del bersaglio in %n scansione…</numerusform>
            <numerusform>Calibrazione: ricerca del bersaglio in %n scansioni…</numerusform>
        </translation>
    </message>
    <message>
        <source>Calibrated: save the calibration file.</source>
        <translation>Calibrato: salvare il file di calibrazione.</translation>
    </message>
    <message>
        <source>%1 calibration from %2 of %3 poses, residuals %4 mm / %5° RMS</source>
        <translation>Calibrazione %1 da %2 di %3 pose, residui %4 mm / %5° RMS</translation>
    </message>
    <message numerus="yes">
        <source>%n pose(s) rejected (see the table)</source>
        <translation>
            <numerusform>%n posa scartata (vedere la tabella)</numerusform>
            <numerusform>%n pose scartate (vedere la tabella)</numerusform>
        </translation>
    </message>
    <message>
        <source>No pose rejected</source>
        <translation>Nessuna posa scartata</translation>
    </message>
    <message>
        <source>%1: position %2, %3, %4 mm, quaternion (w x y z) %5 %6 %7 %8</source>
        <translation>%1: posizione %2, %3, %4 mm, quaternione (w x y z) %5 %6 %7 %8</translation>
    </message>
    <message>
        <source>Eye-to-hand</source>
        <translation>eye-to-hand</translation>
    </message>
    <message>
        <source>Eye-in-hand</source>
        <translation>eye-in-hand</translation>
    </message>
    <message>
        <source>%1 of %2</source>
        <translation>%1 di %2</translation>
    </message>
    <message>
        <source>failed</source>
        <translation>non riuscita</translation>
    </message>
    <message>
        <source>rejected: %1</source>
        <translation>scartata: %1</translation>
    </message>
    <message>
        <source>used</source>
        <translation>usata</translation>
    </message>
    <message>
        <source>Open poses file</source>
        <translation>Apri file delle pose</translation>
    </message>
    <message>
        <source>Poses files (*.json);;All files (*)</source>
        <translation>File delle pose (*.json);;Tutti i file (*)</translation>
    </message>
    <message>
        <source>Open target file</source>
        <translation>Apri file del bersaglio</translation>
    </message>
    <message>
        <source>Target files (*.json);;All files (*)</source>
        <translation>File del bersaglio (*.json);;Tutti i file (*)</translation>
    </message>
    <message>
        <source>Save calibration</source>
        <translation>Salva calibrazione</translation>
    </message>
    <message>
        <source>Calibrations (*.json)</source>
        <translation>Calibrazioni (*.json)</translation>
    </message>
</context>
<context>
    <name>scanpick::core</name>
    <message>
        <source>Scene preprocessing</source>
        <translation>Pre-elaborazione della scena</translation>
    </message>
    <message>
        <source>Object count and clustering</source>
        <translation>Conteggio oggetti e clustering</translation>
    </message>
    <message>
        <source>First-level keypoints</source>
        <translation>Punti chiave di primo livello</translation>
    </message>
    <message>
        <source>Second-level features</source>
        <translation>Feature di secondo livello</translation>
    </message>
    <message>
        <source>Feature matching</source>
        <translation>Abbinamento delle feature</translation>
    </message>
    <message>
        <source>Refinement</source>
        <translation>Rifinitura</translation>
    </message>
</context>
<context>
    <name>scanpick::core::params</name>
    <message>
        <source>Remove floor</source>
        <translation>Rimuovi pavimento</translation>
    </message>
    <message>
        <source>Floor distance</source>
        <translation>Distanza dal pavimento</translation>
    </message>
    <message>
        <source>Planes to remove</source>
        <translation>Piani da rimuovere</translation>
    </message>
    <message>
        <source>Min plane share</source>
        <translation>Quota minima del piano</translation>
    </message>
    <message>
        <source>Bin floor share</source>
        <translation>Quota del fondo del cassone</translation>
    </message>
    <message>
        <source>Remove bin walls</source>
        <translation>Rimuovi le pareti del cassone</translation>
    </message>
    <message>
        <source>Voxel size</source>
        <translation>Dimensione voxel</translation>
    </message>
    <message>
        <source>Split into objects</source>
        <translation>Dividi in oggetti</translation>
    </message>
    <message>
        <source>Count radius r</source>
        <translation>Raggio di conteggio r</translation>
    </message>
    <message>
        <source>Min object size</source>
        <translation>Dimensione minima oggetto</translation>
    </message>
    <message>
        <source>k-means seeding</source>
        <translation>Inizializzazione k-means</translation>
    </message>
    <message>
        <source>k-means iterations</source>
        <translation>Iterazioni k-means</translation>
    </message>
    <message>
        <source>Min cluster size</source>
        <translation>Dimensione minima cluster</translation>
    </message>
    <message>
        <source>Split method</source>
        <translation>Metodo di divisione</translation>
    </message>
    <message>
        <source>Keypoint method</source>
        <translation>Metodo dei punti chiave</translation>
    </message>
    <message>
        <source>Neighbourhood radius Δr</source>
        <translation>Raggio di vicinato Δr</translation>
    </message>
    <message>
        <source>Neig. position range Δp</source>
        <translation>Intervallo di posizione vic. Δp</translation>
    </message>
    <message>
        <source>Gradient sensitivity s</source>
        <translation>Sensibilità del gradiente s</translation>
    </message>
    <message>
        <source>Gradient neighbours n</source>
        <translation>Vicini per il gradiente n</translation>
    </message>
    <message>
        <source>Normal radius</source>
        <translation>Raggio delle normali</translation>
    </message>
    <message>
        <source>Estimator</source>
        <translation>Stimatore</translation>
    </message>
    <message>
        <source>Ransac size</source>
        <translation>Dimensione Ransac</translation>
    </message>
    <message>
        <source>Ransac threshold (lines)</source>
        <translation>Soglia Ransac (linee)</translation>
    </message>
    <message>
        <source>Ransac threshold (circles)</source>
        <translation>Soglia Ransac (cerchi)</translation>
    </message>
    <message>
        <source>Ransac trials</source>
        <translation>Tentativi Ransac</translation>
    </message>
    <message>
        <source>Max features</source>
        <translation>Feature massime</translation>
    </message>
    <message>
        <source>Min circle radius</source>
        <translation>Raggio minimo del cerchio</translation>
    </message>
    <message>
        <source>Max circle radius</source>
        <translation>Raggio massimo del cerchio</translation>
    </message>
    <message>
        <source>Find lines</source>
        <translation>Cerca linee</translation>
    </message>
    <message>
        <source>Find circles</source>
        <translation>Cerca cerchi</translation>
    </message>
    <message>
        <source>Max inlier gap</source>
        <translation>Distacco massimo tra inlier</translation>
    </message>
    <message>
        <source>Sample radius</source>
        <translation>Raggio di campionamento</translation>
    </message>
    <message>
        <source>Matching length Δl</source>
        <translation>Abbinamento lunghezza Δl</translation>
    </message>
    <message>
        <source>Matching radius size</source>
        <translation>Abbinamento raggio</translation>
    </message>
    <message>
        <source>Matching position Δp</source>
        <translation>Abbinamento posizione Δp</translation>
    </message>
    <message>
        <source>Matching orientation Δo</source>
        <translation>Abbinamento orientamento Δo</translation>
    </message>
    <message>
        <source>Roll step</source>
        <translation>Passo di rollio</translation>
    </message>
    <message>
        <source>Score</source>
        <translation>Punteggio</translation>
    </message>
    <message>
        <source>Max detections</source>
        <translation>Rilevamenti massimi</translation>
    </message>
    <message>
        <source>Instances per object</source>
        <translation>Istanze per oggetto</translation>
    </message>
    <message>
        <source>Verify distance</source>
        <translation>Distanza di verifica</translation>
    </message>
    <message>
        <source>Min coverage</source>
        <translation>Copertura minima</translation>
    </message>
    <message>
        <source>Edge distance</source>
        <translation>Distanza dai bordi</translation>
    </message>
    <message>
        <source>Hypotheses</source>
        <translation>Ipotesi</translation>
    </message>
    <message>
        <source>Pose pool</source>
        <translation>Insieme di pose</translation>
    </message>
    <message>
        <source>Surface sampling</source>
        <translation>Campionamento della superficie</translation>
    </message>
    <message>
        <source>Surface reference stride</source>
        <translation>Passo dei riferimenti di superficie</translation>
    </message>
    <message>
        <source>Surface poses</source>
        <translation>Pose di superficie</translation>
    </message>
    <message>
        <source>Near-symmetry overlap</source>
        <translation>Sovrapposizione quasi-simmetria</translation>
    </message>
    <message>
        <source>ICP refinement</source>
        <translation>Rifinitura ICP</translation>
    </message>
    <message>
        <source>ICP iterations</source>
        <translation>Iterazioni ICP</translation>
    </message>
    <message>
        <source>ICP distance</source>
        <translation>Distanza ICP</translation>
    </message>
    <message>
        <source>ICP final distance</source>
        <translation>Distanza finale ICP</translation>
    </message>
    <message>
        <source>Inlier distance</source>
        <translation>Distanza inlier</translation>
    </message>
    <message>
        <source>ICP convergence</source>
        <translation>Convergenza ICP</translation>
    </message>
    <message>
        <source>ICP model points</source>
        <translation>Punti del modello ICP</translation>
    </message>
    <message>
        <source>Point-to-plane</source>
        <translation>Punto-piano</translation>
    </message>
    <message>
        <source>ICP min inliers</source>
        <translation>Inlier minimi ICP</translation>
    </message>
    <message>
        <source>Slide to the ends</source>
        <translation>Scorri fino alle estremità</translation>
    </message>
    <message>
        <source>Slide to the outline</source>
        <translation>Scorri fino al contorno</translation>
    </message>
    <message>
        <source>Random seed</source>
        <translation>Seme casuale</translation>
    </message>
    <message>
        <source>points</source>
        <translation>punti</translation>
    </message>
    <message>
        <source>deg</source>
        <translation>gradi</translation>
    </message>
    <message>
        <source>Remove the dominant planes (bin floor, table) with RANSAC before anything else.</source>
        <translation>Rimuove con RANSAC i piani dominanti (fondo del cassone, tavolo) prima di ogni altra cosa.</translation>
    </message>
    <message>
        <source>Points closer than this to the fitted plane are floor and are removed.</source>
        <translation>I punti più vicini di così al piano stimato sono pavimento e vengono rimossi.</translation>
    </message>
    <message>
        <source>How many dominant planes to remove (1: floor; 5: floor and four bin walls).</source>
        <translation>Quanti piani dominanti rimuovere (1: pavimento; 5: pavimento e le quattro pareti del cassone).</translation>
    </message>
    <message>
        <source>A plane is removed only if it holds at least this fraction of the scene&apos;s points.</source>
        <translation>Un piano viene rimosso solo se contiene almeno questa frazione dei punti della scena.</translation>
    </message>
    <message>
        <source>Beyond the thesis, for a bin standing on the ground: also remove the plane parallel to the first removed one that holds at least this fraction of the scene&apos;s points and has (almost) nothing behind it, the bin&apos;s floor; 0 = off.</source>
        <translation>Oltre la tesi, per un cassone appoggiato a terra: rimuove anche il piano parallelo al primo rimosso che contiene almeno questa frazione dei punti della scena e non ha (quasi) nulla dietro di sé, il fondo del cassone; 0 = disattivato.</translation>
    </message>
    <message>
        <source>Beyond the thesis, after a bin&apos;s floor: also remove the bin&apos;s walls and rim from what forms objects and votes (verification and ICP still see them).</source>
        <translation>Oltre la tesi, dopo il fondo del cassone: rimuove anche le pareti e il bordo del cassone da ciò che forma gli oggetti e vota (verifica e ICP li vedono ancora).</translation>
    </message>
    <message>
        <source>Voxel-grid downsampling of the scene before keypoints; 0 keeps every point.</source>
        <translation>Sottocampionamento a griglia di voxel della scena prima dei punti chiave; 0 mantiene ogni punto.</translation>
    </message>
    <message>
        <source>Count the objects and split the scene with k-means; off treats the scene as one object.</source>
        <translation>Conta gli oggetti e divide la scena con k-means; disattivato tratta la scena come un solo oggetto.</translation>
    </message>
    <message>
        <source>Single-linkage distance r on the scene projected along the line to the farther source (Algorithm 7); the thesis suggests 1-1.5 mm for PhoXi.</source>
        <translation>Distanza di collegamento singolo r sulla scena proiettata lungo la linea verso la sorgente più lontana (Algoritmo 7); la tesi suggerisce 1-1,5 mm per PhoXi.</translation>
    </message>
    <message>
        <source>Projected clusters with at least this many points are counted as objects (min_cluster_size of Algorithm 7).</source>
        <translation>I cluster proiettati con almeno questo numero di punti sono contati come oggetti (min_cluster_size dell&apos;Algoritmo 7).</translation>
    </message>
    <message>
        <source>Initial centres of Lloyd&apos;s k-means: farthest-first traversal (the thesis&apos;s choice, deterministic) or k-means++ (seeded).</source>
        <translation>Centri iniziali del k-means di Lloyd: attraversamento del più lontano (la scelta della tesi, deterministico) o k-means++ (con seme).</translation>
    </message>
    <message>
        <source>Upper bound on Lloyd iterations; it stops earlier when the objective stops decreasing.</source>
        <translation>Limite superiore alle iterazioni di Lloyd; si ferma prima quando l&apos;obiettivo smette di diminuire.</translation>
    </message>
    <message>
        <source>k-means clusters smaller than this are outliers: their points are removed and k-means is re-run (the thesis uses 3).</source>
        <translation>I cluster k-means più piccoli di così sono anomali: i loro punti vengono rimossi e k-means viene rieseguito (la tesi usa 3).</translation>
    </message>
    <message>
        <source>k-means with k = the object count (the thesis), or the projected clusters of the count used directly as objects (keeps touching parts apart; small fragments join the nearest object).</source>
        <translation>k-means con k = il numero di oggetti (la tesi), oppure i cluster proiettati del conteggio usati direttamente come oggetti (tiene separati i pezzi che si toccano; i piccoli frammenti si uniscono all&apos;oggetto più vicino).</translation>
    </message>
    <message>
        <source>Neighbourhood analysis (edges, Algorithm 2), normals gradient analysis (curvature peaks, Algorithm 1), or both together.</source>
        <translation>Analisi del vicinato (spigoli, Algoritmo 2), analisi del gradiente delle normali (picchi di curvatura, Algoritmo 1), o entrambe insieme.</translation>
    </message>
    <message>
        <source>Radius of the neighbourhood whose centroid is examined.</source>
        <translation>Raggio del vicinato di cui si esamina il baricentro.</translation>
    </message>
    <message>
        <source>A point is an edge keypoint when its neighbourhood centroid is at least this far away; a negative value keeps every point (the thesis&apos;s ideal test uses -1).</source>
        <translation>Un punto è un punto chiave di spigolo quando il baricentro del suo vicinato dista almeno così; un valore negativo mantiene ogni punto (il test ideale della tesi usa -1).</translation>
    </message>
    <message>
        <source>Normals gradient analysis: a point whose neighbours&apos; normals all turn less than s is in a flat region and yields no keypoint.</source>
        <translation>Analisi del gradiente delle normali: un punto le cui normali vicine ruotano tutte meno di s è in una regione piana e non dà alcun punto chiave.</translation>
    </message>
    <message>
        <source>Normals gradient analysis: neighbours examined at each step of the walk.</source>
        <translation>Analisi del gradiente delle normali: vicini esaminati a ogni passo del percorso.</translation>
    </message>
    <message>
        <source>Radius of the neighbourhood used to estimate surface normals.</source>
        <translation>Raggio del vicinato usato per stimare le normali della superficie.</translation>
    </message>
    <message>
        <source>Sample-consensus estimator for lines and circles; the thesis keeps RANSAC, which finds more features than MLESAC and PROSAC.</source>
        <translation>Stimatore a consenso di campioni per linee e cerchi; la tesi mantiene RANSAC, che trova più feature di MLESAC e PROSAC.</translation>
    </message>
    <message>
        <source>Minimum inliers of an accepted line or circle.</source>
        <translation>Inlier minimi di una linea o di un cerchio accettati.</translation>
    </message>
    <message>
        <source>Distance within which a keypoint is an inlier of a line.</source>
        <translation>Distanza entro la quale un punto chiave è un inlier di una linea.</translation>
    </message>
    <message>
        <source>Distance within which a keypoint is an inlier of a circle.</source>
        <translation>Distanza entro la quale un punto chiave è un inlier di un cerchio.</translation>
    </message>
    <message>
        <source>Random samples drawn per line or circle search.</source>
        <translation>Campioni casuali estratti per ogni ricerca di linea o cerchio.</translation>
    </message>
    <message>
        <source>Stop extracting after this many lines and circles per cloud.</source>
        <translation>Interrompe l&apos;estrazione dopo questo numero di linee e cerchi per nuvola.</translation>
    </message>
    <message>
        <source>Circles with a smaller radius are rejected.</source>
        <translation>I cerchi con raggio minore vengono scartati.</translation>
    </message>
    <message>
        <source>Circles with a larger radius are rejected.</source>
        <translation>I cerchi con raggio maggiore vengono scartati.</translation>
    </message>
    <message>
        <source>Search 3D lines.</source>
        <translation>Cerca linee 3D.</translation>
    </message>
    <message>
        <source>Search 3D circles.</source>
        <translation>Cerca cerchi 3D.</translation>
    </message>
    <message>
        <source>A line&apos;s or circle&apos;s inliers are cut where neighbours along it are farther apart than this and only the largest connected run is kept, so collinear edges of different objects do not merge; 0 = automatic.</source>
        <translation>Gli inlier di una linea o di un cerchio vengono interrotti dove i vicini lungo di essa distano più di così e si mantiene solo il tratto connesso più lungo, così gli spigoli allineati di oggetti diversi non si fondono; 0 = automatico.</translation>
    </message>
    <message>
        <source>Beyond the thesis: the other points of a RANSAC sample are drawn within this distance of its first point, so features are found in far fewer trials; 0 = uniform sampling (the thesis).</source>
        <translation>Oltre la tesi: gli altri punti di un campione RANSAC sono estratti entro questa distanza dal primo, così le feature si trovano con molti meno tentativi; 0 = campionamento uniforme (la tesi).</translation>
    </message>
    <message>
        <source>Two lines may match when their lengths differ by at most this.</source>
        <translation>Due linee possono corrispondere quando le loro lunghezze differiscono al massimo di così.</translation>
    </message>
    <message>
        <source>Two circles may match when their radii differ by at most this.</source>
        <translation>Due cerchi possono corrispondere quando i loro raggi differiscono al massimo di così.</translation>
    </message>
    <message>
        <source>Radius around the predicted position (on the roll toroid, and after the transform when scoring) within which a scene feature is accepted.</source>
        <translation>Raggio attorno alla posizione prevista (sul toroide di rollio, e dopo la trasformazione nel calcolo del punteggio) entro il quale una feature della scena è accettata.</translation>
    </message>
    <message>
        <source>Largest angle between predicted and found feature directions (line axis or circle normal).</source>
        <translation>Angolo massimo tra la direzione prevista e quella trovata di una feature (asse della linea o normale del cerchio).</translation>
    </message>
    <message>
        <source>Angular step of the search around T1&apos;s axis (the toroid of Figure 3.5).</source>
        <translation>Passo angolare della ricerca attorno all&apos;asse di T1 (il toroide della Figura 3.5).</translation>
    </message>
    <message>
        <source>Detections whose share of confirmed model features is below this are rejected.</source>
        <translation>I rilevamenti la cui quota di feature del modello confermate è inferiore a questa vengono scartati.</translation>
    </message>
    <message>
        <source>Report at most this many detections, best first; 0 = all.</source>
        <translation>Riporta al massimo questo numero di rilevamenti, i migliori per primi; 0 = tutti.</translation>
    </message>
    <message>
        <source>Searches per scene cluster: after a detection its features are removed and the cluster is searched again, since clustering may merge touching parts.</source>
        <translation>Ricerche per cluster della scena: dopo un rilevamento le sue feature vengono rimosse e il cluster viene cercato di nuovo, poiché il clustering può unire pezzi che si toccano.</translation>
    </message>
    <message>
        <source>Beyond the thesis: a pose is verified by the share of model points with a scene point within this distance, less those the camera sees through (organized scans); 0 = off (the thesis&apos;s feature score only).</source>
        <translation>Oltre la tesi: una posa è verificata dalla quota di punti del modello con un punto della scena entro questa distanza, meno quelli attraverso cui la camera vede (scansioni organizzate); 0 = disattivato (solo il punteggio delle feature della tesi).</translation>
    </message>
    <message>
        <source>With verification on: detections confirming a smaller share of their visible model points are rejected.</source>
        <translation>Con la verifica attiva: i rilevamenti che confermano una quota minore dei loro punti visibili del modello vengono scartati.</translation>
    </message>
    <message>
        <source>Beyond the thesis: with verification on, the coverage is also weighed by the share of the model&apos;s keypoints (edges) lying on confirmed surface that have a scene keypoint within this distance, so a plate turned on another plate scores low; 0 = off.</source>
        <translation>Oltre la tesi: con la verifica attiva, la copertura è pesata anche dalla quota di punti chiave (spigoli) del modello che giacciono su superficie confermata e hanno un punto chiave della scena entro questa distanza, così una piastra ruotata su un&apos;altra piastra ottiene un punteggio basso; 0 = disattivato.</translation>
    </message>
    <message>
        <source>Distinct poses per search re-ranked by verification; 1 = the thesis (the best feature score alone decides).</source>
        <translation>Pose distinte per ricerca riordinate dalla verifica; 1 = la tesi (decide solo il miglior punteggio delle feature).</translation>
    </message>
    <message>
        <source>Beyond the thesis, for bins of touching parts: with verification on, one search keeps up to this many distinct poses from all seed pairs, verifies each and reports every one reaching the min coverage (instead of repeated best-first searches); 0 = off.</source>
        <translation>Oltre la tesi, per cassoni di pezzi che si toccano: con la verifica attiva, una ricerca conserva fino a questo numero di pose distinte da tutte le coppie iniziali, verifica ciascuna e riporta ognuna che raggiunge la copertura minima (invece di ricerche ripetute del migliore); 0 = disattivato.</translation>
    </message>
    <message>
        <source>Beyond the thesis: with verification on, surface point pair voting adds pose hypotheses that need no line or circle pairs (parts whose edges are hidden by their neighbours); model and scene are sampled with voxels of this edge, about 4 % of the part&apos;s diameter; 0 = off.</source>
        <translation>Oltre la tesi: con la verifica attiva, il voto su coppie di punti di superficie aggiunge ipotesi di posa che non richiedono coppie di linee o cerchi (pezzi i cui spigoli sono nascosti dai vicini); modello e scena sono campionati con voxel di questo lato, circa il 4 % del diametro del pezzo; 0 = disattivato.</translation>
    </message>
    <message>
        <source>Surface voting: every n-th sampled scene point votes as a reference; lower finds more (partly hidden) parts, higher is faster.</source>
        <translation>Voto di superficie: ogni n-esimo punto campionato della scena vota come riferimento; più basso trova più pezzi (in parte nascosti), più alto è più veloce.</translation>
    </message>
    <message>
        <source>Surface voting: at most this many voted poses (most votes first) are refined and verified.</source>
        <translation>Voto di superficie: al massimo questo numero di pose votate (le più votate per prime) viene rifinito e verificato.</translation>
    </message>
    <message>
        <source>Beyond the thesis, for nearly symmetric parts (a plate whose hook differs only at its lip): a turn of the view, found by voting the view against itself, that puts this share of its points back on its own surface is a near symmetry; each detection is compared with its turned pose on the points that differ, and the pose the scan contradicts clearly less is kept, or both are reported when it cannot tell. Needs verification; 0 = off.</source>
        <translation>Oltre la tesi, per pezzi quasi simmetrici (una piastra il cui gancio differisce solo al bordo): una rotazione della vista, trovata facendo votare la vista contro se stessa, che riporta questa quota dei suoi punti sulla propria superficie è una quasi-simmetria; ogni rilevamento è confrontato con la sua posa ruotata sui punti che differiscono, e si mantiene la posa che la scansione contraddice chiaramente meno, oppure si riportano entrambe quando non si può decidere. Richiede la verifica; 0 = disattivato.</translation>
    </message>
    <message>
        <source>Refine each detection&apos;s pose with ICP against the scene points; views that know their place in the part fit the other views&apos; points too, and several views&apos; detections are refined after they are merged.</source>
        <translation>Rifinisce la posa di ogni rilevamento con ICP sui punti della scena; le viste che conoscono la propria posizione nel pezzo adattano anche i punti delle altre viste, e i rilevamenti di più viste vengono rifiniti dopo essere stati uniti.</translation>
    </message>
    <message>
        <source>Upper bound on ICP iterations.</source>
        <translation>Limite superiore alle iterazioni ICP.</translation>
    </message>
    <message>
        <source>Model-scene point pairs farther apart than this are ignored by ICP.</source>
        <translation>Le coppie di punti modello-scena più distanti di così sono ignorate da ICP.</translation>
    </message>
    <message>
        <source>The pair distance shrinks from the ICP distance towards 3x the residual, but not below this; about 5-10x the sensor noise (PhoXi 1 mm, Kinect 10 mm).</source>
        <translation>La distanza delle coppie si riduce dalla distanza ICP verso 3 volte il residuo, ma non sotto questo valore; circa 5-10 volte il rumore del sensore (PhoXi 1 mm, Kinect 10 mm).</translation>
    </message>
    <message>
        <source>A visible model point with a scene point this close confirms the refined pose.</source>
        <translation>Un punto visibile del modello con un punto della scena così vicino conferma la posa rifinita.</translation>
    </message>
    <message>
        <source>ICP stops when an iteration moves no model point by more than this.</source>
        <translation>ICP si ferma quando un&apos;iterazione non sposta alcun punto del modello di più di così.</translation>
    </message>
    <message>
        <source>Model points used by ICP (an even voxel subsample); more is slower, rarely better.</source>
        <translation>Punti del modello usati da ICP (un sottocampionamento uniforme a voxel); di più è più lento, raramente migliore.</translation>
    </message>
    <message>
        <source>Minimise point-to-plane distances (fast, sub-sample accurate); off: point-to-point.</source>
        <translation>Minimizza le distanze punto-piano (veloce, precisione inferiore al passo di campionamento); disattivato: punto-punto.</translation>
    </message>
    <message>
        <source>A refined pose counts as converged only if this share of the visible model points has a scene point within the inlier distance.</source>
        <translation>Una posa rifinita conta come convergente solo se questa quota dei punti visibili del modello ha un punto della scena entro la distanza inlier.</translation>
    </message>
    <message>
        <source>After ICP, a view that is a surface of revolution (a cup or pipe on its side) is slid along its axis to where the scan shows its wall&apos;s two ends, which ICP hardly pins; the middle between the ends is where the part&apos;s middle is, whatever the pixel size.</source>
        <translation>Dopo ICP, una vista che è una superficie di rivoluzione (una tazza o un tubo coricati) viene fatta scorrere lungo il suo asse fino a dove la scansione mostra le due estremità della parete, che ICP vincola appena; il punto medio tra le estremità è dove sta il centro del pezzo, qualunque sia la dimensione del pixel.</translation>
    </message>
    <message>
        <source>After ICP, a view that is no surface of revolution is moved along each direction ICP hardly pins (a plate seen face-on, in its own plane), or pins loosely where both sides agree within 0.1 mm (a plate seen edge-on, along its length), to where the scan&apos;s points end as the view&apos;s do, both sides of the outline together; other views of the part tell where this view&apos;s ends were hidden when it was taught. ICP then leaves the directions it hardly pins as they came, for the outline to place. Helps plates; a view cut from a cluttered scan can lose by it.</source>
        <translation>Dopo ICP, una vista che non è una superficie di rivoluzione viene spostata lungo ogni direzione che ICP vincola appena (una piastra vista di fronte, nel proprio piano), o vincola debolmente dove i due lati concordano entro 0,1 mm (una piastra vista di taglio, lungo la sua lunghezza), fino a dove i punti della scansione finiscono come quelli della vista, entrambi i lati del contorno insieme; le altre viste del pezzo dicono dove le estremità di questa vista erano nascoste quando è stata insegnata. ICP lascia poi le direzioni che vincola appena come sono arrivate, perché le collochi il contorno. Aiuta le piastre; una vista ritagliata da una scansione affollata può perderci.</translation>
    </message>
    <message>
        <source>Seed of every random choice; the same input and seed give the same output.</source>
        <translation>Seme di ogni scelta casuale; lo stesso ingresso e lo stesso seme danno lo stesso risultato.</translation>
    </message>
    <message>
        <source>mm</source>
        <translation>mm</translation>
    </message>
    <message>
        <source>rad</source>
        <translation>rad</translation>
    </message>
    <message>
        <source>farthest_first</source>
        <translation>più lontano prima</translation>
    </message>
    <message>
        <source>kmeans++</source>
        <translation>k-means++</translation>
    </message>
    <message>
        <source>kmeans</source>
        <translation>k-means</translation>
    </message>
    <message>
        <source>projected_clusters</source>
        <translation>cluster proiettati</translation>
    </message>
    <message>
        <source>neighbourhood</source>
        <translation>vicinato</translation>
    </message>
    <message>
        <source>normals_gradient</source>
        <translation>gradiente delle normali</translation>
    </message>
    <message>
        <source>both</source>
        <translation>entrambi</translation>
    </message>
    <message>
        <source>ransac</source>
        <translation>RANSAC</translation>
    </message>
    <message>
        <source>mlesac</source>
        <translation>MLESAC</translation>
    </message>
    <message>
        <source>prosac</source>
        <translation>PROSAC</translation>
    </message>
</context>
<context>
    <name>scanpick::presets</name>
    <message>
        <source>Thesis table 5.7: coat rack recognition, configuration 0 (relaxed constraints, PhoXi). The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults.</source>
        <translation>Tabella 5.7 della tesi: riconoscimento dell&apos;appendiabiti, configurazione 0 (vincoli rilassati, PhoXi). Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti.</translation>
    </message>
    <message>
        <source>Thesis table 5.8: coat rack recognition, configuration 1 (strict constraints for the greatest precision, PhoXi). The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults.</source>
        <translation>Tabella 5.8 della tesi: riconoscimento dell&apos;appendiabiti, configurazione 1 (vincoli stretti per la massima precisione, PhoXi). Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti.</translation>
    </message>
    <message>
        <source>Thesis table 5.4: cup recognition (PhoXi). The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults.</source>
        <translation>Tabella 5.4 della tesi: riconoscimento della tazza (PhoXi). Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti.</translation>
    </message>
    <message>
        <source>Thesis table 5.3: support and ornament detection in a scene of several object types (PhoXi); for the jar use detection-jar. The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults.</source>
        <translation>Tabella 5.3 della tesi: rilevamento del supporto e dell&apos;ornamento in una scena con oggetti di più tipi (PhoXi); per il barattolo usare detection-jar. Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti.</translation>
    </message>
    <message>
        <source>Thesis table 5.3 for the jar in a scene of several object types (PhoXi): as detection but with score 0.4, as §5.2 says, because the jar&apos;s simple shape gives few features. The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults.</source>
        <translation>Tabella 5.3 della tesi per il barattolo in una scena con oggetti di più tipi (PhoXi): come detection ma con punteggio 0,4, come dice il §5.2, perché la forma semplice del barattolo dà poche caratteristiche. Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti.</translation>
    </message>
    <message>
        <source>Thesis table 5.1: the test in an ideal environment without noise (a model of two circles and two lines). The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults. Ransac threshold &apos;1/10^-3 mm [circles/lines]&apos; means circles 1 mm, lines 0.001 mm; position range -1 keeps every point (the thesis skips first-level keypoints here).</source>
        <translation>Tabella 5.1 della tesi: la prova in un ambiente ideale senza rumore (un modello di due cerchi e due linee). Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti. Ransac threshold &apos;1/10^-3 mm [cerchi/linee]&apos; significa cerchi 1 mm, linee 0,001 mm; un position range di -1 tiene ogni punto (qui la tesi salta i punti chiave di primo livello).</translation>
    </message>
    <message>
        <source>Thesis table 5.2: the test in an ideal environment with noise in the target scene. The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults. Ransac threshold &apos;1/0.5 mm [circles/lines]&apos; means circles 1 mm, lines 0.5 mm.</source>
        <translation>Tabella 5.2 della tesi: la prova in un ambiente ideale con rumore nella scena. Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti. Ransac threshold &apos;1/0.5 mm [cerchi/linee]&apos; significa cerchi 1 mm, linee 0,5 mm.</translation>
    </message>
    <message>
        <source>Thesis table 5.6: Kinect v1 recognition (rabbit ornament, pears). The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation. The table&apos;s &apos;Ransac size 0&apos; is below the parameter&apos;s minimum and is set to 2: a line needs 2 points and a circle 3, so every line and circle RANSAC finds passes, as with 0. What scales with the sensor&apos;s point spacing (about 2 mm at 1 m) the table leaves out is set for the Kinect&apos;s noise: a 10 mm neighbourhood radius, normals over 10 mm, a 10 mm floor distance, objects counted with a 6 mm linkage radius and 500 points, verification within 5 mm.</source>
        <translation>Tabella 5.6 della tesi: riconoscimento con Kinect v1 (ornamento a coniglio, pere). Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation. Il &apos;Ransac size 0&apos; della tabella è sotto il minimo del parametro ed è posto a 2: una linea richiede 2 punti e un cerchio 3, quindi ogni linea e cerchio trovati da RANSAC passano, come con 0. Ciò che dipende dalla spaziatura dei punti del sensore (circa 2 mm a 1 m) la tabella lo omette ed è impostato per il rumore del Kinect: raggio di vicinato di 10 mm, normali su 10 mm, distanza dal pavimento di 10 mm, oggetti contati con un raggio di collegamento di 6 mm e 500 punti, verifica entro 5 mm.</translation>
    </message>
    <message>
        <source>Kinect v1 bin picking (millimetre-to-centimetre depth noise, points about 2 mm apart at 1 m), parts in a bin or on a table: a 10 mm floor distance, projected clusters linked within 6 mm, 8 mm neighbourhoods, normals over 10 mm, surface point pair voting (8 mm sampling, polished by ICP) and no line or circle search (a part seen by a Kinect holds too few points for two line or circle pairs), point-level verification within 5 mm with a 0.8 minimum coverage. A fixed set-up for comparison: with no preset, teach derives every value from the part and the scan.</source>
        <translation>Bin picking con Kinect v1 (rumore di profondità da millimetri a centimetri, punti a circa 2 mm l&apos;uno dall&apos;altro a 1 m), pezzi in un contenitore o su un tavolo: distanza dal pavimento di 10 mm, cluster proiettati collegati entro 6 mm, vicinati di 8 mm, normali su 10 mm, voto su coppie di punti di superficie (campionamento di 8 mm, rifinito con ICP) e nessuna ricerca di linee o cerchi (un pezzo visto da un Kinect ha troppo pochi punti per due coppie di linee o cerchi), verifica punto per punto entro 5 mm con copertura minima 0,8. Una configurazione fissa per confronto: senza preset, teach ricava ogni valore dal pezzo e dalla scansione.</translation>
    </message>
    <message>
        <source>PhoXi M bin picking (about 0.1 mm depth noise, points about 0.7 mm apart at 1 m), parts in a bin or on a table: the ground and a bin&apos;s floor removed (on a table or a tray set floor.bin_floor_fraction=0, so that the top faces of parts lying flat stay), projected clusters, tight RANSAC thresholds and matching tolerances, a pooled search over all seed pairs (touching parts), surface point pair voting (5 mm sampling, every 16th scene point votes, 30 voted poses verified, polished by ICP), point-level verification (1 mm, normals agreeing, edges within 2 mm) with a 0.65 minimum coverage, and the near-symmetry check: a rotation that puts 75 % of a view back on itself is checked against the scan on the points where the two differ, or reported as an alternative pose. A fixed set-up for comparison: with no preset, teach derives every value from the part and the scan.</source>
        <translation>Bin picking con PhoXi M (rumore di profondità di circa 0,1 mm, punti a circa 0,7 mm l&apos;uno dall&apos;altro a 1 m), pezzi in un contenitore o su un tavolo: pavimento e fondo del contenitore rimossi (su un tavolo o un vassoio impostare floor.bin_floor_fraction=0, perché le facce superiori dei pezzi appoggiati di piatto restino), cluster proiettati, soglie RANSAC e tolleranze di corrispondenza strette, una ricerca comune su tutte le coppie iniziali (pezzi a contatto), voto su coppie di punti di superficie (campionamento di 5 mm, vota un punto della scena ogni 16, 30 pose votate verificate, rifinite con ICP), verifica punto per punto (1 mm, normali concordi, bordi entro 2 mm) con copertura minima 0,65, e il controllo delle quasi simmetrie: una rotazione che riporta il 75 % di una vista su sé stessa è confrontata con la scansione sui punti in cui le due differiscono, o riportata come posa alternativa. Una configurazione fissa per confronto: senza preset, teach ricava ogni valore dal pezzo e dalla scansione.</translation>
    </message>
    <message>
        <source>Thesis table 5.5: pump component recognition (PhoXi, Euclid Labs bin-picking scans). The table&apos;s columns are Ransac size, Ransac threshold [circles/lines], Neig. position range, Score (&apos;-&apos; = 0) and Matching length / radius size / position / orientation; other keys keep their defaults.</source>
        <translation>Tabella 5.5 della tesi: riconoscimento del componente di pompa (PhoXi, scansioni di bin picking di Euclid Labs). Le colonne della tabella sono Ransac size, Ransac threshold [cerchi/linee], Neig. position range, Score (&apos;-&apos; = 0) e Matching length / radius size / position / orientation; le altre chiavi mantengono i valori predefiniti.</translation>
    </message>
    <message>
        <source>The thesis&apos;s own method with its default values (chapter 3): k-means clustering, first-level keypoints, RANSAC lines and circles, feature matching with the roll search; no point-level verification, no surface voting, no refinement. For comparison: with no preset, teach derives every value from the part and the scan instead.</source>
        <translation>Il metodo della tesi con i suoi valori predefiniti (capitolo 3): clustering k-means, punti chiave di primo livello, linee e cerchi RANSAC, corrispondenza delle caratteristiche con la ricerca del rollio; nessuna verifica punto per punto, nessun voto sulle superfici, nessuna rifinitura. Per confronto: senza preset, l&apos;insegnamento ricava ogni valore dal pezzo e dalla scansione.</translation>
    </message>
</context>
</TS>
